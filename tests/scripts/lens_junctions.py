"""Where the lens's haptics meet its optic (meshes/iol/lens.geo),
computed here from the lens's dimensions, independently of lens.geo: the
corners where each haptic edge crosses the optic rim, and the fillets of
junction_fillet = f, tangent to the rim and to the edge. Used to check
that a filleted lens's mesh has no corner left and that its outline
follows the fillets.

The lens lies in z = 0; the second haptic is the first turned by 180
degrees about the z axis. The first haptic leaves the optic at y < 0:
  - C-loop: its edges are the circles of radii haptic_radius -+ width / 2
    about (rho, 0), rho = overall / 2 - width / 2 - haptic_radius;
  - modified-L: its leg's edges are the lines k0 + s d -+ (width / 2) n,
    n = (-d_y, d_x), where the leg is tangent to a knee of centre-line
    radius knee_radius turning by knee_angle into an arm of radius
    arm_radius about (overall / 2 - width / 2 - arm_radius, 0) that
    starts at arm_start degrees (README: the IOL scenes, the lens).
"""
import math

import numpy as np


class CircleEdge:
    """A circle: how far points are from it, and where along it (the
    angle about its centre)."""

    def __init__(self, centre, radius):
        self.centre, self.radius = np.asarray(centre, float), radius

    def distance(self, points):
        return np.abs(np.linalg.norm(points - self.centre, axis=-1)
                      - self.radius)

    def offset(self, points, start):
        """Along the circle from start, in radians, in (-pi, pi]."""
        def angle(p):
            p = np.asarray(p) - self.centre
            return np.arctan2(p[..., 1], p[..., 0])
        return (angle(points) - angle(start) + np.pi) % (2 * np.pi) - np.pi

    def turned(self):
        return CircleEdge(-self.centre, self.radius)


class LineEdge:
    """A straight line through point along the unit direction."""

    def __init__(self, point, direction):
        self.point = np.asarray(point, float)
        self.direction = np.asarray(direction, float)

    def distance(self, points):
        relative = points - self.point
        return np.abs(relative[..., 0] * self.direction[1]
                      - relative[..., 1] * self.direction[0])

    def offset(self, points, start):
        return (np.asarray(points) - np.asarray(start)) @ self.direction

    def turned(self):
        return LineEdge(-self.point, -self.direction)


def c_loop_fillets(fillet, rim, overall, width, haptic_radius):
    """The first C-loop's two junctions: (edge, corner, fillet centre,
    tangent point on the edge)."""
    rho = overall / 2 - width / 2 - haptic_radius
    found = []
    for side in (-1, 1):  # inner edge, outer edge
        radius = haptic_radius + side * width / 2
        # Corner: the rim and the edge circle, below the x axis.
        cx = (rim**2 - radius**2 + rho**2) / (2 * rho)
        corner = np.array([cx, -math.sqrt(rim**2 - cx**2)])
        # Fillet centre: rim + f from the lens centre and radius + side f
        # from the edge's centre (outside the outer edge's circle, inside
        # the inner's).
        far, from_edge = rim + fillet, radius + side * fillet
        px = (far**2 - from_edge**2 + rho**2) / (2 * rho)
        centre = np.array([px, -math.sqrt(far**2 - px**2)])
        edge = CircleEdge((rho, 0.0), radius)
        on_edge = edge.centre + (centre - edge.centre) * radius / from_edge
        found.append((edge, corner, centre, on_edge))
    return found


def leaving(point, direction, radius):
    """Where the line point + s direction leaves the circle of this
    radius about the origin (the larger s)."""
    along = point @ direction
    s = -along + math.sqrt(along**2 - point @ point + radius**2)
    return point + s * direction


def modified_l_fillets(fillet, rim, overall, width, knee_radius=0.6,
                       knee_angle=90.0, arm_radius=4.5, arm_start=-70.0):
    """The first modified-L's two junctions, on its leg's two edges."""
    arm_centre = overall / 2 - width / 2 - arm_radius
    beta = math.radians(arm_start)
    knee = np.array([arm_centre + (arm_radius - knee_radius) * math.cos(beta),
                     (arm_radius - knee_radius) * math.sin(beta)])
    gamma = beta - math.radians(knee_angle)
    knee_start = knee + knee_radius * np.array([math.cos(gamma),
                                                math.sin(gamma)])
    direction = np.array([-math.sin(gamma), math.cos(gamma)])
    normal = np.array([-direction[1], direction[0]])
    found = []
    for side in (1, -1):  # towards the knee's centre, away from it
        edge_point = knee_start + side * width / 2 * normal
        corner = leaving(edge_point, direction, rim)
        centre = leaving(edge_point + side * fillet * normal, direction,
                         rim + fillet)
        found.append((LineEdge(edge_point, direction), corner, centre,
                      centre - side * fillet * normal))
    return found


def junctions(fillet, haptic_type=0, optic_radius=3.0, overall=13.0,
              width=0.4, haptic_radius=3.8):
    """Per junction (four): the edge (a CircleEdge or LineEdge), the
    corner, the fillet's centre and its tangent points on the rim and on
    the edge."""
    if haptic_type == 0:
        first = c_loop_fillets(fillet, optic_radius, overall, width,
                               haptic_radius)
    else:
        first = modified_l_fillets(fillet, optic_radius, overall, width)
    found = []
    for edge, corner, centre, on_edge in first:
        on_rim = centre * optic_radius / (optic_radius + fillet)
        for turn in (1.0, -1.0):  # the second haptic: turned by pi
            found.append({"edge": edge if turn > 0 else edge.turned(),
                          "corner": turn * corner, "centre": turn * centre,
                          "on_rim": turn * on_rim, "on_edge": turn * on_edge})
    return found


def boundary_vertices(cells):
    """Indices of the vertices on the mesh's outline: those of the edges
    that belong to one triangle only."""
    count = {}
    for triangle in cells:
        for a, b in ((0, 1), (1, 2), (2, 0)):
            edge = tuple(sorted((int(triangle[a]), int(triangle[b]))))
            count[edge] = count.get(edge, 0) + 1
    return sorted({v for edge, n in count.items() if n == 1 for v in edge})


def between(edge, points, start, end, margin=1e-6):
    """Whether each point lies along the edge from start (included) to
    end (not included); on a circle, an arc of less than pi."""
    span = edge.offset(end, start)
    offset = edge.offset(points, start) * np.sign(span)
    return (offset > -margin) & (offset < abs(span) - margin)


def check_fillets(checks, points, cells, fillet, haptic_type=0,
                  optic_radius=3.0, tolerance=1e-4):
    """Checks a filleted lens's rest mesh (points in mm, triangles):
    every outline vertex near the optic lies on the rim, a haptic edge or
    a fillet arc (between its tangent points); each fillet carries
    outline vertices, among them both tangent points; and the rim and the
    haptic's edge stop at the tangent points, short of the sharp lens's
    corner, which the fillet fills."""
    xy = np.asarray(points)[:, :2]
    outline = xy[boundary_vertices(cells)]
    near = outline[np.hypot(outline[:, 0], outline[:, 1])
                   < optic_radius + 2 * fillet + 0.3]
    places = junctions(fillet, haptic_type, optic_radius)
    rim = CircleEdge((0.0, 0.0), optic_radius)
    on_rim = rim.distance(near)
    on_something = on_rim < tolerance
    for junction in places:
        edge = junction["edge"]
        on_edge = edge.distance(near)
        on_fillet = np.abs(np.linalg.norm(near - junction["centre"], axis=1)
                           - fillet) < tolerance
        on_something |= (on_edge < tolerance) | on_fillet
        ends = [np.min(np.linalg.norm(near - junction[key], axis=1))
                for key in ("on_rim", "on_edge")]
        checks(f"the fillet about ({junction['centre'][0]:.4f}, "
               f"{junction['centre'][1]:.4f}) carries {int(on_fillet.sum())} "
               f"outline vertices (at least 2), its tangent points among "
               f"them (off by {max(ends):.2g} mm)",
               on_fillet.sum() >= 2 and max(ends) < tolerance)
        # Filled, the rim and the edge stop at the fillet's tangent points:
        # none of their outline vertices lies from the corner to either.
        inside = (on_rim < tolerance) & between(
            rim, near, junction["corner"], junction["on_rim"])
        inside |= (on_edge < tolerance) & between(
            edge, near, junction["corner"], junction["on_edge"])
        checks(f"the rim and the edge have no outline vertex from the "
               f"sharp lens's corner ({junction['corner'][0]:.4f}, "
               f"{junction['corner'][1]:.4f}) to the fillet's tangent "
               f"points (found {int(inside.sum())})", not inside.any())
    checks(f"each of the {len(near)} outline vertices within "
           f"{optic_radius + 2 * fillet + 0.3:g} mm of the lens centre lies "
           "on the rim, a haptic edge or a fillet", bool(on_something.all()))


def check_refinement(checks, points, cells, fillet, size, radius,
                     haptic_type=0, optic_radius=3.0):
    """Checks a lens refined at its junctions (lens.geo junction_mesh_size
    = size within radius mm of each fillet's disk, or of each corner when
    fillet = 0), on the triangles whose centroid lies that near: the
    median of their longest edges is at most 1.2 size and 95 % of them
    are shorter than 1.5 size (gmsh's at 0.95 to 1.05 and 1.16 to 1.36
    there on the halved lens; the largest, at the zone's border, up to
    1.9), and there are at least as many as a fifth of the disk's ring
    holds at that size. No lower bound: a short fillet's outline points
    make smaller triangles (0.79 size at the median on the coarse lens's
    outer fillets at size 0.12)."""
    xy = np.asarray(points)[:, :2]
    corners = xy[np.asarray(cells)]
    centroids = corners.mean(axis=1)
    longest = np.max(np.linalg.norm(
        corners - np.roll(corners, 1, axis=1), axis=2), axis=1)
    ring = math.pi * ((fillet + radius)**2 - fillet**2)
    least = int(0.2 * ring / (math.sqrt(3) / 4 * size**2))
    for junction in junctions(fillet, haptic_type, optic_radius):
        near = (np.linalg.norm(centroids - junction["centre"], axis=1)
                - fillet) < radius
        median, upper = (np.percentile(longest[near], (50, 95)) / size
                         if near.any() else (0.0, 0.0))
        checks(f"the {int(near.sum())} triangles within {radius:g} mm of "
               f"the junction at ({junction['centre'][0]:.4f}, "
               f"{junction['centre'][1]:.4f}) (at least {least}): longest "
               f"edges {median:.2f} junction_mesh_size at the median "
               f"(at most 1.2), {upper:.2f} at the 95th percentile "
               "(at most 1.5)",
               near.sum() >= least and median <= 1.2 and upper <= 1.5)
