#!/usr/bin/python3
"""Headless pictures of a CoShell run: the shell and its rigid obstacles.

Reads the VTU files that coshell writes (deal.II 9.4 DataOut::write_vtu for
the shell, coshell's own ASCII writer for the obstacles), either through the
run's solution.pvd collection (part 0: the shell, part 1 and up: obstacles)
or as one shell file, and writes PNG images drawn with matplotlib's 3-D axes
(Agg backend: no display, no VTK). Standard library, numpy and matplotlib
only.

The shell's Points are its reference positions (coshell builds the patches
with a plain P1 mapping, no displacement), so the script draws
Points + warp_scale * displacement; the obstacle files already hold the
obstacles' current positions.

  render_vtu.py --pvd OUT/solution.pvd [--times T ... | --all | --last]
                --out PREFIX [--montage FILE.png] [options]
      writes PREFIX-<index>.png per selected time, <index> being the time's
      position (from 0) in the collection; --montage also puts the selected
      times side by side in one figure (e.g. a deployment sequence).
  render_vtu.py --vtu solution-00004.vtu --out FILE.png [options]
      one shell file; its obstacles-NNNNN.vtu neighbour is drawn if present.

Options: --color-by material_id|thickness|displacement_magnitude|none or any
point/cell array name (vectors are shown by their magnitude), --view ELEV
AZIM, --obstacle-alpha, --title, --no-obstacles, --edges, --fit all|shell,
--warp-scale, --cmap, --size, --dpi, --no-axes.

Example:
  /usr/bin/python3 doc/scripts/render_vtu.py --pvd output/funnel/solution.pvd \\
      --all --out /tmp/funnel --montage /tmp/funnel-sequence.png --edges
"""
import argparse
import base64
import math
import os
import re
import sys
import xml.etree.ElementTree as ElementTree
import zlib
from dataclasses import dataclass, field

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import cm, colors  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

# VTK's DataArray type names and their numpy kinds (byte order added later).
VTK_NUMPY_TYPES = {
    "Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2",
    "Int32": "i4", "UInt32": "u4", "Int64": "i8", "UInt64": "u8",
    "Float32": "f4", "Float64": "f8",
}

# Surface cell types and how many of their first vertices are the corners:
# higher-order cells list the corners first, and the flat facet through the
# corners is all a matplotlib polygon can show anyway. None: use them all.
SURFACE_CELL_CORNERS = {
    5: None,   # VTK_TRIANGLE
    7: None,   # VTK_POLYGON
    9: None,   # VTK_QUAD
    22: 3,     # VTK_QUADRATIC_TRIANGLE
    23: 4,     # VTK_QUADRATIC_QUAD
    28: 4,     # VTK_BIQUADRATIC_QUAD
    69: 3,     # VTK_LAGRANGE_TRIANGLE (deal.II's higher-order output)
    70: 4,     # VTK_LAGRANGE_QUADRILATERAL
}

SPECIAL_FIELDS = ("material_id", "thickness", "displacement_magnitude", "none")
SHELL_PLAIN_COLOUR = "lightsteelblue"
OBSTACLE_COLOUR = "0.55"


# --------------------------------------------------------------------------
# Reading VTU files
# --------------------------------------------------------------------------

@dataclass
class VtuMesh:
    """One UnstructuredGrid piece, its surface cells flattened.

    Cell c has the vertices cell_vertices[cell_starts[c]:][:cell_sizes[c]].
    """
    points: np.ndarray
    cell_vertices: np.ndarray
    cell_starts: np.ndarray
    cell_sizes: np.ndarray
    point_data: dict = field(default_factory=dict)
    cell_data: dict = field(default_factory=dict)

    @property
    def n_cells(self):
        return len(self.cell_sizes)


def numpy_type(vtk_type, byte_order):
    if vtk_type not in VTK_NUMPY_TYPES:
        raise ValueError(f"unsupported DataArray type '{vtk_type}'")
    prefix = ">" if byte_order == "BigEndian" else "<"
    return np.dtype(prefix + VTK_NUMPY_TYPES[vtk_type])


def decode_compressed_array(text, header_type):
    """Bytes of a base64 array written with vtkZLibDataCompressor.

    The header [n_blocks, block_size, last_block_size, compressed sizes...]
    is base64-encoded on its own, and the concatenated zlib blocks after it,
    so the header's length in characters must be known before decoding.
    """
    word = header_type.itemsize
    # The header holds at least three words, so these characters decode to
    # n_blocks without reaching any padding.
    first = base64.b64decode(text[:4 * math.ceil(word / 3)])
    n_blocks = int(np.frombuffer(first[:word], header_type)[0])
    header_chars = 4 * math.ceil(word * (3 + n_blocks) / 3)
    header = np.frombuffer(base64.b64decode(text[:header_chars]), header_type,
                           count=3 + n_blocks).astype(np.int64)
    block_size, last_block_size = header[1], header[2]
    compressed = base64.b64decode(text[header_chars:])
    pieces, position = [], 0
    for size in header[3:]:
        pieces.append(zlib.decompress(compressed[position:position + size]))
        position += size
    data = b"".join(pieces)
    # VTK writes 0 as the last block's size when that block is full.
    expected = (n_blocks - 1) * block_size + (last_block_size or block_size)
    if n_blocks and len(data) != expected:
        raise ValueError(f"decompressed {len(data)} bytes, header says {expected}")
    return data


def decode_uncompressed_array(text, header_type):
    """Bytes of a base64 array without compressor: [n_bytes] then the data.

    Writers differ on whether the byte count is encoded on its own (then its
    base64 ends in padding) or in one stream with the data; both are read.
    """
    word = header_type.itemsize
    header_chars = 4 * math.ceil(word / 3)
    if word % 3 and text[header_chars - 1:header_chars] == "=":
        n_bytes = int(np.frombuffer(base64.b64decode(text[:header_chars]),
                                    header_type)[0])
        data = base64.b64decode(text[header_chars:])
    else:
        joint = base64.b64decode(text)
        n_bytes = int(np.frombuffer(joint[:word], header_type)[0])
        data = joint[word:]
    return data[:n_bytes]


def read_data_array(element, file_attributes):
    """A DataArray element as a numpy array of shape (n,) or (n, components)."""
    dtype = numpy_type(element.get("type"), file_attributes.get("byte_order"))
    data_format = element.get("format", "ascii")
    text = element.text or ""
    if data_format == "ascii":
        values = np.array(text.split(), dtype=np.float64).astype(dtype)
    elif data_format == "binary":
        header_type = numpy_type(file_attributes.get("header_type", "UInt32"),
                                 file_attributes.get("byte_order"))
        compact = "".join(text.split())
        if file_attributes.get("compressor"):
            raw = decode_compressed_array(compact, header_type)
        else:
            raw = decode_uncompressed_array(compact, header_type)
        values = np.frombuffer(raw, dtype)
    else:
        # deal.II never writes appended data; say so instead of misreading.
        raise ValueError(f"DataArray format '{data_format}' is not supported")
    components = int(element.get("NumberOfComponents", "1"))
    return values.reshape(-1, components) if components > 1 else values


def named_arrays(section, file_attributes):
    if section is None:
        return {}
    return {array.get("Name"): read_data_array(array, file_attributes)
            for array in section.findall("DataArray")}


def surface_cells(connectivity, offsets, types):
    """Flattened corner lists of the polygonal cells (lines and points are
    dropped: nothing to shade)."""
    ends = offsets.astype(np.int64)
    starts = np.concatenate(([0], ends[:-1]))
    keep = np.isin(types, list(SURFACE_CELL_CORNERS))
    corner_counts = np.array([SURFACE_CELL_CORNERS[t] or (e - s) for t, s, e
                              in zip(types[keep], starts[keep], ends[keep])],
                             dtype=np.int64)
    starts = starts[keep]
    if len(starts) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64)
    # Gather each kept cell's first corner_counts vertices in one go.
    cell_of_entry = np.repeat(np.arange(len(starts)), corner_counts)
    new_starts = np.concatenate(([0], np.cumsum(corner_counts)[:-1]))
    rank_in_cell = np.arange(corner_counts.sum()) - new_starts[cell_of_entry]
    vertices = connectivity[starts[cell_of_entry] + rank_in_cell]
    return vertices.astype(np.int64), new_starts, corner_counts


def read_vtu(path):
    root = ElementTree.parse(path).getroot()
    if root.get("type") != "UnstructuredGrid":
        raise ValueError(f"{path}: not an UnstructuredGrid VTU file")
    pieces = root.findall("./UnstructuredGrid/Piece")
    if len(pieces) != 1:
        raise ValueError(f"{path}: expected one Piece, found {len(pieces)}")
    piece, attributes = pieces[0], root.attrib
    points_element = piece.find("./Points/DataArray")
    points = (read_data_array(points_element, attributes).astype(np.float64)
              .reshape(-1, 3) if points_element is not None else np.zeros((0, 3)))
    cells = named_arrays(piece.find("Cells"), attributes)
    if len(points) != int(piece.get("NumberOfPoints", len(points))):
        raise ValueError(f"{path}: {len(points)} points, header says "
                         f"{piece.get('NumberOfPoints')}")
    if cells and len(cells["offsets"]):
        vertices, starts, sizes = surface_cells(
            cells["connectivity"], cells["offsets"], cells["types"])
    else:  # an obstacle file with no triangles
        vertices = starts = sizes = np.zeros(0, np.int64)
    return VtuMesh(points, vertices, starts, sizes,
                   named_arrays(piece.find("PointData"), attributes),
                   named_arrays(piece.find("CellData"), attributes))


@dataclass
class Frame:
    """The files of one time of a .pvd collection."""
    index: int
    time: float
    shell_file: str = None
    obstacle_files: list = field(default_factory=list)


def read_pvd(path):
    """The collection's frames in file order. coshell lists each time's
    shell (part 0) before its obstacle files (parts 1, 2...); a new frame
    starts at each shell entry, so a time written twice stays two frames."""
    root = ElementTree.parse(path).getroot()
    directory = os.path.dirname(os.path.abspath(path))
    frames = []
    for entry in root.iter("DataSet"):
        time = float(entry.get("timestep", "0"))
        file_name = os.path.join(directory, entry.get("file"))
        is_shell = int(entry.get("part", "0")) == 0
        if is_shell or not frames or frames[-1].time != time:
            frames.append(Frame(len(frames), time))
        if is_shell:
            frames[-1].shell_file = file_name
        else:
            frames[-1].obstacle_files.append(file_name)
    missing = [f.time for f in frames if f.shell_file is None]
    if missing:
        raise ValueError(f"{path}: no shell (part 0) file at times {missing}")
    return frames


def select_frames(frames, times, want_all):
    """The requested frames; a requested time picks the nearest one written."""
    if want_all:
        return frames
    if not times:
        return frames[-1:]
    chosen = []
    for wanted in times:
        nearest = min(frames, key=lambda f: abs(f.time - wanted))
        if not math.isclose(nearest.time, wanted, rel_tol=1e-9, abs_tol=1e-12):
            print(f"time {wanted:g} not written; using t = {nearest.time:g}")
        if nearest not in chosen:
            chosen.append(nearest)
    return chosen


def neighbour_obstacle_file(shell_file):
    """obstacles-NNNNN.vtu written next to solution-NNNNN.vtu, if any."""
    directory, name = os.path.split(shell_file)
    match = re.fullmatch(r"solution(-\d+)?\.vtu", name)
    if not match:
        return []
    candidate = os.path.join(directory, f"obstacles{match.group(1) or ''}.vtu")
    return [candidate] if os.path.exists(candidate) else []


# --------------------------------------------------------------------------
# Geometry and colours
# --------------------------------------------------------------------------

@dataclass
class Faces:
    """Polygons in space: an (n, k, 3) array when all have k corners,
    else a list of (k_i, 3) arrays (both are what Poly3DCollection takes)."""
    polygons: object

    def __len__(self):
        return len(self.polygons)

    def normals(self):
        """Unnormalised normals, (n, 3): the sum of the fan triangles' cross
        products, which stays right for clipped polygons whose first three
        corners may be in line."""
        if isinstance(self.polygons, np.ndarray):
            return polygon_normal(self.polygons)
        return np.array([polygon_normal(p) for p in self.polygons]).reshape(-1, 3)

    def all_corners(self):
        if isinstance(self.polygons, np.ndarray):
            return self.polygons.reshape(-1, 3)
        return np.concatenate(self.polygons) if self.polygons else np.zeros((0, 3))


def polygon_normal(corners):
    """Fan-sum normal of one polygon (k, 3) or of many (n, k, 3)."""
    from_first = corners[..., 1:, :] - corners[..., :1, :]
    return np.cross(from_first[..., :-1, :], from_first[..., 1:, :]).sum(axis=-2)


def mesh_faces(mesh, positions):
    sizes = mesh.cell_sizes
    if len(sizes) and np.all(sizes == sizes[0]):
        return Faces(positions[mesh.cell_vertices.reshape(-1, sizes[0])])
    return Faces([positions[mesh.cell_vertices[s:s + n]]
                  for s, n in zip(mesh.cell_starts, sizes)])


def join_faces(first, second):
    a, b = first.polygons, second.polygons
    if isinstance(a, np.ndarray) and isinstance(b, np.ndarray) \
            and a.shape[1:] == b.shape[1:]:
        return Faces(np.concatenate((a, b)))
    return Faces(list(a) + list(b))


def deformed_positions(mesh, warp_scale):
    """Current shell positions: deal.II wrote the reference Points."""
    displacement = mesh.point_data.get("displacement")
    if displacement is None:
        return mesh.points
    return mesh.points + warp_scale * displacement.astype(np.float64)


def cell_means(mesh, values):
    """Per-cell mean of point values (exact for deal.II's cell data, which
    it writes as point data repeated on each cell's own vertices)."""
    sums = np.add.reduceat(values[mesh.cell_vertices], mesh.cell_starts, axis=0)
    return sums / mesh.cell_sizes.reshape((-1,) + (1,) * (values.ndim - 1))


def cell_field(mesh, name):
    """A cell field of a deal.II VTU (written as point data), one float64
    value per cell."""
    return cell_means(mesh, mesh.point_data[name].astype(np.float64))


def face_values(mesh, field_name):
    """(per-cell values, colour-bar label) of the field to colour by."""
    if field_name == "none":
        return None, None
    base, label = field_name, field_name
    if field_name.endswith("_magnitude") and field_name not in mesh.point_data \
            and field_name not in mesh.cell_data:
        base = field_name[:-len("_magnitude")]
        label = f"|{base}|"
    if base in mesh.cell_data:
        values = mesh.cell_data[base].astype(np.float64)
    elif base in mesh.point_data and mesh.n_cells:
        values = cell_means(mesh, mesh.point_data[base].astype(np.float64))
    elif base in mesh.point_data:
        values = np.zeros(0)
    else:
        known = sorted(set(mesh.point_data) | set(mesh.cell_data))
        raise SystemExit(f"no array '{base}' to colour by; the file has {known}")
    if values.ndim > 1:  # vectors and tensors: their magnitude
        values, label = np.linalg.norm(values, axis=1), f"|{base}|"
    return values, label


def view_direction(elevation, azimuth):
    """Unit vector from the scene towards matplotlib's camera."""
    e, a = np.radians(elevation), np.radians(azimuth)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def lambert_factors(faces, light):
    """Brightness per face from its normal; |n.l| because a shell has no
    inside, and an ambient floor keeps edge-on faces from going black."""
    if len(faces) == 0:
        return np.zeros(0)
    normals = faces.normals()
    lengths = np.linalg.norm(normals, axis=1)
    lengths[lengths == 0] = 1.0
    return 0.4 + 0.6 * np.abs(normals @ light) / lengths


# --------------------------------------------------------------------------
# Scenes: what is drawn at one time
# --------------------------------------------------------------------------

@dataclass
class Scene:
    time: float
    label: str
    shell: Faces
    shell_values: np.ndarray
    field_label: str
    obstacles: Faces
    panel_label: str = None  # --labels: named above the time in a montage


def load_scene(shell_file, obstacle_files, time, args):
    shell_mesh = read_vtu(shell_file)
    shell = mesh_faces(shell_mesh, deformed_positions(shell_mesh, args.warp_scale))
    values, field_label = face_values(shell_mesh, args.color_by)
    obstacles = Faces(np.zeros((0, 3, 3)))
    if not args.no_obstacles:
        for obstacle_file in obstacle_files:
            mesh = read_vtu(obstacle_file)
            obstacles = join_faces(obstacles, mesh_faces(mesh, mesh.points))
    return Scene(time, os.path.basename(shell_file), shell, values,
                 field_label, obstacles)


def scene_bounds(scenes, fit):
    """(low, high) corners around every scene, so that all images of a run
    share one box. --fit shell boxes the shell with a margin of 15 % of its
    size, enough to show what it rests on or is pushed by."""
    corners = [s.shell.all_corners() for s in scenes]
    if fit == "all":
        corners += [s.obstacles.all_corners() for s in scenes]
    corners = np.concatenate([c for c in corners if len(c)] or [np.zeros((1, 3))])
    low, high = corners.min(axis=0), corners.max(axis=0)
    # A flat shell has no extent across it: the margin also gives that axis
    # a thickness, on the same scale as the others.
    margin = 0.15 if fit == "shell" else 0.01
    pad = max(float(np.max(high - low)), 1e-12) * margin
    return low - pad, high + pad


def clip_polygon(corners, low, high):
    """The part of a planar polygon inside the box (Sutherland-Hodgman, one
    face of the box after the other), or None when nothing is left."""
    for axis in range(3):
        for bound, side in ((low[axis], 1.0), (high[axis], -1.0)):
            inside = side * (corners[:, axis] - bound)
            kept = []
            for i in range(len(corners)):
                j = (i + 1) % len(corners)
                if inside[i] >= 0:
                    kept.append(corners[i])
                if (inside[i] >= 0) != (inside[j] >= 0):
                    fraction = inside[i] / (inside[i] - inside[j])
                    kept.append(corners[i] + fraction * (corners[j] - corners[i]))
            if len(kept) < 3:
                return None
            corners = np.array(kept)
    return corners


def clip_faces(faces, low, high):
    """The faces cut to the box: matplotlib 3.6 does not clip 3-D artists to
    the axes limits, so obstacles larger than the box would spill out."""
    if len(faces) == 0:
        return faces
    polygons = list(faces.polygons)
    inside = [np.all((p >= low) & (p <= high)) for p in polygons]
    if all(inside):
        return faces
    clipped = [p if whole else clip_polygon(p, low, high)
               for p, whole in zip(polygons, inside)]
    return Faces([p for p in clipped if p is not None])


def colour_mapping(scenes, args):
    """(colormap, norm) shared by all scenes, or (None, None) for 'none'."""
    values = [s.shell_values for s in scenes if s.shell_values is not None]
    values = np.concatenate(values) if values else np.zeros(0)
    if args.color_by == "none" or len(values) == 0:
        return None, None
    low, high = float(values.min()), float(values.max())
    if args.color_by == "material_id":
        # Categories: one flat colour per integer id, the same id getting
        # the same colour whatever other ids the run has.
        ids = np.arange(math.floor(low), math.ceil(high) + 1)
        palette = plt.get_cmap("tab10")
        colormap = colors.ListedColormap([palette(i % 10) for i in ids])
        return colormap, colors.BoundaryNorm(np.append(ids - 0.5, ids[-1] + 0.5),
                                             len(ids))
    if high - low <= 1e-12 * max(abs(high), 1.0):
        low, high = low - 0.5 * max(abs(low), 1.0), high + 0.5 * max(abs(high), 1.0)
    return plt.get_cmap(args.cmap), colors.Normalize(low, high)


# --------------------------------------------------------------------------
# Drawing
# --------------------------------------------------------------------------

def face_colours(scene, colouring, args):
    """(face RGBA, edge RGBA) for the shell's faces then the obstacles'."""
    colormap, norm = colouring
    # A headlight raised 30 degrees above the camera: a plate seen at a
    # low angle still catches the light, and tilted facets stand out.
    elevation, azimuth = args.view
    light = view_direction(min(elevation + 30.0, 90.0), azimuth)
    if norm is not None:
        shell = colormap(norm(scene.shell_values))
    else:
        shell = np.tile(colors.to_rgba(SHELL_PLAIN_COLOUR), (len(scene.shell), 1))
    shell[:, :3] *= lambert_factors(scene.shell, light)[:, None]
    obstacle = np.tile(colors.to_rgba(OBSTACLE_COLOUR, args.obstacle_alpha),
                       (len(scene.obstacles), 1))
    obstacle[:, :3] *= lambert_factors(scene.obstacles, light)[:, None]
    # Without --edges each face is outlined in its own colour, which hides
    # the hairline seams antialiasing leaves between neighbouring triangles.
    shell_edges = (np.tile(colors.to_rgba("black", 0.6), (len(shell), 1))
                   if args.edges else shell.copy())
    obstacle_edges = obstacle.copy()
    obstacle_edges[:, 3] = min(1.0, 2.0 * args.obstacle_alpha)
    return np.vstack((shell, obstacle)), np.vstack((shell_edges, obstacle_edges))


def draw_scene(axes, scene, bounds, colouring, args, title):
    # One collection for shell and obstacles: matplotlib orders polygons by
    # depth only within a collection, so two would overlap wrongly.
    faces = join_faces(scene.shell, scene.obstacles)
    face_rgba, edge_rgba = face_colours(scene, colouring, args)
    if len(faces):
        # Linewidths are not reordered with the depth sort, so they are one
        # value for all faces; the edge colours carry the differences.
        axes.add_collection3d(Poly3DCollection(
            faces.polygons, facecolors=face_rgba, edgecolors=edge_rgba,
            linewidths=0.25 if args.edges else 0.3))
    low, high = bounds
    axes.set_xlim(low[0], high[0])
    axes.set_ylim(low[1], high[1])
    axes.set_zlim(low[2], high[2])
    # Equal scaling: the box's sides in proportion to the data's ranges.
    axes.set_box_aspect(high - low)
    axes.view_init(elev=args.view[0], azim=args.view[1])
    if args.no_axes:
        axes.set_axis_off()
    else:
        axes.set_xlabel("x")
        axes.set_ylabel("y")
        axes.set_zlabel("z")
        axes.tick_params(labelsize=7)
        # Fewer ticks on short sides, whose labels would otherwise overlap,
        # and none across a flat scene, where any two would.
        longest = float(np.max(high - low))
        for axis, extent in zip((axes.xaxis, axes.yaxis, axes.zaxis), high - low):
            if extent < 0.05 * longest:
                axis.set_ticks([])
            else:
                axis.set_major_locator(
                    MaxNLocator(max(2, round(6 * extent / longest))))
    axes.set_title(title, fontsize=10)


def add_colour_bar(figure, axes, colouring, field_label, below=False):
    """A labelled colour bar right of the axes (clear of the z label), or
    below them for a montage's row of panels."""
    colormap, norm = colouring
    if norm is None:
        return
    placement = (dict(location="bottom", shrink=0.4, pad=0.06, aspect=40) if below
                 else dict(location="right", shrink=0.6, pad=0.12))
    bar = figure.colorbar(cm.ScalarMappable(norm=norm, cmap=colormap), ax=axes,
                          label=field_label, **placement)
    if isinstance(norm, colors.BoundaryNorm):
        bar.set_ticks(0.5 * (norm.boundaries[:-1] + norm.boundaries[1:]))
        bar.set_ticklabels([str(int(round(b + 0.5))) for b in norm.boundaries[:-1]])


def scene_title(scene, args):
    when = f"t = {scene.time:g}" if scene.time is not None else scene.label
    return f"{args.title}\n{when}" if args.title else when


def render_one(scene, bounds, colouring, args, path):
    figure = plt.figure(figsize=args.size)
    axes = figure.add_subplot(projection="3d")
    draw_scene(axes, scene, bounds, colouring, args, scene_title(scene, args))
    add_colour_bar(figure, axes, colouring, scene.field_label)
    save(figure, path, args.dpi)


def render_montage(scenes, bounds, colouring, args, path):
    """The scenes side by side (rows of --montage-columns), one shared box
    and colour scale so that the panels compare directly."""
    columns = min(len(scenes), args.montage_columns)
    rows = math.ceil(len(scenes) / columns)
    # Square panels: a 3-D axes fits its box into the square on its shorter
    # side, so any extra width would only be empty space.
    panel = 0.7 * min(args.size)
    figure = plt.figure(figsize=(panel * columns, panel * rows + 0.8))
    all_axes = []
    for number, scene in enumerate(scenes):
        axes = figure.add_subplot(rows, columns, number + 1, projection="3d")
        when = f"t = {scene.time:g}" if scene.time is not None else scene.label
        draw_scene(axes, scene, bounds, colouring, args,
                   f"{scene.panel_label}\n{when}" if scene.panel_label
                   else when)
        all_axes.append(axes)
    # 3-D panels carry wide empty margins of their own: pack them closer.
    figure.subplots_adjust(left=0.02, right=0.98, wspace=0.02, hspace=0.1,
                           top=1.0 - 0.3 / figure.get_figheight())
    if args.title:
        # Above the figure's top edge, clear of the panels' titles; the
        # tight bounding box at saving takes it in.
        figure.suptitle(args.title, y=1.0 + 0.2 / figure.get_figheight())
    add_colour_bar(figure, all_axes, colouring, scenes[0].field_label, below=True)
    save(figure, path, args.dpi)


def save(figure, path, dpi):
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    # A 3-D box leaves wide margins in its figure; crop them.
    figure.savefig(path, dpi=dpi, bbox_inches="tight", pad_inches=0.15)
    plt.close(figure)
    print(f"wrote {path}")


# --------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------

def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("--pvd", help="a run's solution.pvd")
    source.add_argument("--vtu", help="one shell solution file")
    which = parser.add_mutually_exclusive_group()
    which.add_argument("--times", type=float, nargs="+",
                       help="times to draw (the nearest written ones)")
    which.add_argument("--all", action="store_true", help="every time written")
    which.add_argument("--last", action="store_true",
                       help="the last time written (the default)")
    parser.add_argument("--out", help="--pvd: prefix of PREFIX-<index>.png; "
                        "--vtu: the PNG file")
    parser.add_argument("--montage", help="also one PNG with the selected times "
                        "side by side")
    parser.add_argument("--montage-columns", type=int, default=4)
    parser.add_argument("--labels", nargs="+",
                        help="with --times: a name per time (e.g. the stage), "
                        "above each panel's time")
    parser.add_argument("--color-by", default="displacement_magnitude",
                        help=f"{'|'.join(SPECIAL_FIELDS)} or an array name")
    parser.add_argument("--cmap", default="viridis")
    parser.add_argument("--view", type=float, nargs=2, default=(30.0, -60.0),
                        metavar=("ELEV", "AZIM"), help="camera angles, degrees")
    parser.add_argument("--obstacle-alpha", type=float, default=0.15)
    parser.add_argument("--title", default="")
    parser.add_argument("--no-obstacles", action="store_true")
    parser.add_argument("--edges", action="store_true", help="draw mesh edges")
    parser.add_argument("--fit", choices=("all", "shell"), default="all",
                        help="box around shell and obstacles, or the shell only")
    parser.add_argument("--warp-scale", type=float, default=1.0,
                        help="displacement magnification (0: reference shape)")
    parser.add_argument("--size", type=float, nargs=2, default=(8.0, 6.0),
                        metavar=("WIDTH", "HEIGHT"), help="inches")
    parser.add_argument("--dpi", type=int, default=150)
    parser.add_argument("--no-axes", action="store_true")
    args = parser.parse_args(argv)
    if not args.out and not args.montage:
        parser.error("give --out and/or --montage")
    if args.vtu and (args.times or args.all):
        parser.error("--times/--all need --pvd")
    if args.labels and len(args.labels) != len(args.times or []):
        parser.error("--labels needs one label per time of --times")
    return args


def load_scenes(args):
    """[(scene, output path or None)] for the selected times."""
    if args.vtu:
        scene = load_scene(args.vtu, neighbour_obstacle_file(args.vtu), None, args)
        return [(scene, args.out)]
    frames = select_frames(read_pvd(args.pvd), args.times, args.all)
    scenes = [(load_scene(f.shell_file, f.obstacle_files, f.time, args),
               f"{args.out}-{f.index:04d}.png" if args.out else None)
              for f in frames]
    if args.labels:
        if len(frames) != len(args.labels):
            sys.exit(f"{len(args.labels)} labels for {len(frames)} frames: "
                     "two times picked the same frame")
        for (scene, _), label in zip(scenes, args.labels):
            scene.panel_label = label
    return scenes


def main(argv=None):
    args = parse_arguments(argv)
    scenes_and_paths = load_scenes(args)
    scenes = [scene for scene, _ in scenes_and_paths]
    bounds = scene_bounds(scenes, args.fit)
    if args.fit == "shell":
        for scene in scenes:
            scene.obstacles = clip_faces(scene.obstacles, *bounds)
    colouring = colour_mapping(scenes, args)
    for scene, path in scenes_and_paths:
        if path:
            render_one(scene, bounds, colouring, args, path)
    if args.montage:
        render_montage(scenes, bounds, colouring, args, args.montage)


if __name__ == "__main__":
    sys.exit(main())
