"""Where the C-loop lens's haptics meet its optic (meshes/iol/lens.geo),
computed here from the lens's dimensions, independently of lens.geo: the
corners where each haptic edge crosses the optic rim, and the fillets of
junction_fillet = f, tangent to the rim and to the edge. Used to check
that a filleted lens's mesh has no corner left and that its outline
follows the fillets.

The lens lies in z = 0. The first haptic's edges are the circles of radii
haptic_radius -+ width / 2 about (rho, 0), rho = overall / 2 - width / 2
- haptic_radius; it leaves the optic at y < 0. The second is the first
turned by 180 degrees about the z axis.
"""
import math

import numpy as np


def junctions(fillet, optic_radius=3.0, overall=13.0, width=0.4,
              haptic_radius=3.8):
    """Per junction (four): the corner, the fillet's centre, the edge
    circle's centre and radius, and the tangent points on the rim and on
    the edge."""
    rho = overall / 2 - width / 2 - haptic_radius
    rim = optic_radius
    found = []
    for side in (-1, 1):  # inner edge, outer edge
        edge = haptic_radius + side * width / 2
        # Corner: the rim and the edge circle, below the x axis.
        cx = (rim**2 - edge**2 + rho**2) / (2 * rho)
        corner = np.array([cx, -math.sqrt(rim**2 - cx**2)])
        # Fillet centre: rim + f from the lens centre and edge + side f
        # from the edge's centre (outside the outer edge's circle, inside
        # the inner's).
        far = rim + fillet
        from_edge = edge + side * fillet
        px = (far**2 - from_edge**2 + rho**2) / (2 * rho)
        centre = np.array([px, -math.sqrt(far**2 - px**2)])
        edge_centre = np.array([rho, 0.0])
        on_rim = centre * rim / far
        on_edge = edge_centre + (centre - edge_centre) * edge / from_edge
        for turn in (1.0, -1.0):  # the second haptic: turned by pi
            found.append({"corner": turn * corner, "centre": turn * centre,
                          "edge_centre": turn * edge_centre,
                          "edge_radius": edge, "on_rim": turn * on_rim,
                          "on_edge": turn * on_edge})
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


def between(points, centre, start, end, margin=1e-6):
    """Whether each point's angle about centre lies from that of start
    (included) to that of end (not included), an arc of less than pi."""
    def angle(p):
        return np.arctan2(p[..., 1] - centre[1], p[..., 0] - centre[0])
    span = (angle(end) - angle(start) + np.pi) % (2 * np.pi) - np.pi
    offset = (angle(points) - angle(start) + np.pi) % (2 * np.pi) - np.pi
    return (offset * np.sign(span) > -margin) \
        & (offset * np.sign(span) < abs(span) - margin)


def check_fillets(checks, points, cells, fillet, optic_radius=3.0,
                  tolerance=1e-4):
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
    places = junctions(fillet, optic_radius)
    on_rim = np.abs(np.hypot(near[:, 0], near[:, 1]) - optic_radius)
    on_something = on_rim < tolerance
    for junction in places:
        on_edge = np.abs(np.linalg.norm(near - junction["edge_centre"],
                                        axis=1) - junction["edge_radius"])
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
            near, np.zeros(2), junction["corner"], junction["on_rim"])
        inside |= (on_edge < tolerance) & between(
            near, junction["edge_centre"], junction["corner"],
            junction["on_edge"])
        checks(f"the rim and the edge have no outline vertex from the "
               f"sharp lens's corner ({junction['corner'][0]:.4f}, "
               f"{junction['corner'][1]:.4f}) to the fillet's tangent "
               f"points (found {int(inside.sum())})", not inside.any())
    checks(f"each of the {len(near)} outline vertices within "
           f"{optic_radius + 2 * fillet + 0.3:g} mm of the lens centre lies "
           "on the rim, a haptic edge or a fillet", bool(on_something.all()))
