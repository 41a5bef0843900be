"""Every tolerance of kinepoly, named, in one place.

Grouped by what they bound: the arithmetic itself, directions and lines (sines, no unit), points and
numbers that are the same (relative to a size), angles, iterations (Newton and its kin), the
cross-check, what is printed, and lengths on the paper (mm). Where one number bounds two different
things it has two names.
"""

__all__ = [
    "ANGLE_SAME_DEG",
    "ANGLE_SAME_RAD",
    "ASSEMBLY_REL_TOL",
    "AT_INFINITY_REL",
    "BOX_FLOOR",
    "COINCIDENT_REL",
    "COINCIDENT_SIN",
    "CONTACT_DISTINCT_REL",
    "COLLINEAR_SIN",
    "CURVES_CONFORMING",
    "CURVES_STRAIGHT",
    "EDIT_SAME_REL",
    "FIT_MARGIN_REL",
    "LAST_BITS_REL",
    "LOOP_SINGULAR_DET",
    "LOUD_ERROR",
    "NEAR_SINGULAR_CONDITION",
    "NEAR_SINGULAR_ERROR",
    "NEAR_SINGULAR_SIN",
    "NEWTON_CLOSED_REL",
    "NEWTON_LEAST_STEP",
    "NEWTON_REL_TOL",
    "NOISE_REL",
    "PAPER_AREA_FLOOR_MM2",
    "PAPER_EXACT_MM",
    "PAPER_ROUNDING_MM",
    "PAPER_SAME_MM",
    "PARALLEL_SIN",
    "PHASE_TOLERANCE",
    "PRINTED_ZERO",
    "RIGID_REL_TOL",
    "ROUNDING_REL",
    "SAME_REL",
    "SINGULAR_CONDITION",
    "SIZE_FLOOR",
    "STRAIGHT_CURVATURE",
    "TINY_POSITIVE",
    "TRACKED_REL",
    "TRACKED_TURN_RAD",
    "UNIT_ROUNDOFF",
]

# --- the arithmetic -------------------------------------------------------------------------------

UNIT_ROUNDOFF = 2.0**-53
"""u: half the spacing of doubles near 1."""

TINY_POSITIVE = 1e-300
"""The least positive value kept where a size, a sine or a scale must not reach 0 (any unit): a quotient by
it stays finite, and it is far below any real size yet above the subnormals."""

LAST_BITS_REL = 1e-15
"""Two numbers that differ by less than this, relative, differ in their last bits only (about 4.5 u): an
angle that is a whole number of quarter turns, a converged Newton step on a spline's parameter (relative
to its period)."""

SIZE_FLOOR = 1e-9
"""A mechanism's or a plot's extent (its own unit: the scene's length, a plot's axis) is taken as at least
this, so that a test relative to it, or a ratio by it, has something to scale by."""

BOX_FLOOR = 1e-12
"""A mechanism's box is taken as at least this wide (the scene's length) when the centers near it are
looked for."""

# --- directions and lines (sines of angles, no unit) ----------------------------------------------

PARALLEL_SIN = 1e-12
"""Two construction lines whose angle has a sine below this are parallel: no finite crossing (also a
unit direction's component below this: the direction lies along the other axis)."""

NEAR_SINGULAR_SIN = 1e-4
"""Below this sine two construction lines still cross, with a near-singular warning."""

COLLINEAR_SIN = 0.2
"""An image triangle flatter than this is built by proportional division instead of two angles."""

COINCIDENT_SIN = 1e-10
"""Two points (or two lines) whose unit homogeneous vectors in a local frame make an angle with a
sine below this are one point (one line): no line runs through them (they meet in no one point)."""

STRAIGHT_CURVATURE = 1e-12
"""A spline's curvature (1/length) below this times its size's inverse (relative, no unit) counts as 0:
the profile is straight there."""

CURVES_STRAIGHT = 1e-9
"""Where two profiles touch (curve on curve), a curvature times the profiles' size (no unit) below this
leaves that profile's centre of curvature at infinity: no equivalent link joins the two centres."""

CURVES_CONFORMING = 1e-6
"""Where two profiles touch, (1/rho1 + 1/rho2) times the profiles' size (no unit) at or below this: the
curves conform or cut into each other, and the link joining the two centres has no length."""

# --- the same point, the same number (relative to a size, no unit) --------------------------------

ROUNDING_REL = 1e-12
"""Two numbers computed along different short paths (a scale and its round value, a full turn, a
matrix's entry beside its largest, an angle and 0 rad) that differ by less than this
times their size are equal: the rounding of a few dozen operations."""

COINCIDENT_REL = 1e-12
"""Two points closer than this times the mechanism's (the polygon's) size are one point: a scene's
points given twice, a tip at the pole, a contact on the cam's centre."""

AT_INFINITY_REL = 1e9
"""An instant center farther than this many times the mechanism's size is taken to be at infinity."""

ASSEMBLY_REL_TOL = 1e-12
"""Relative slack allowed when a circle just touches another circle or a line (a dead point)."""

CONTACT_DISTINCT_REL = 1e-7
"""Two roots of one row's contact (curve on curve) nearer than this times the profiles' size, with poses
turned by less than this in radians, are one contact counted twice."""

SAME_REL = 1e-9
"""Two results of a solve (a sweep's last row against its first, a gear ratio against a fraction, a
seed against a grid point, a written value read back, two polygon points) that differ by less than
this, relative, are the same: far above the construction's own error, far below any real difference."""

TRACKED_REL = 1e-6
"""A solve's points within this (relative to the mechanism's size) of a tracked pose (a sweep's row, a
variant's read-back) are on the same assembly."""

EDIT_SAME_REL = 1e-6
"""Two places of an edit in the editor closer than this (relative to the scene's size) are one place."""

# --- angles ---------------------------------------------------------------------------------------

ANGLE_SAME_RAD = 1e-9
"""Two angles (rad) that differ by less than this are the same angle (a link's vector at theta + 180 deg,
a named line at theta, a link's turn over a closed sweep)."""

ANGLE_SAME_DEG = 1e-9
"""An angle in degrees this close to -180 (180) is written as 180, the end of (-180, 180] it belongs to."""

TRACKED_TURN_RAD = 1e-6
"""A gear turned further than this (rad) by a sweep than a solve at the same input takes it gets its
phase set from the sweep."""

# --- iterations -----------------------------------------------------------------------------------

NEWTON_REL_TOL = 1e-12
"""Newton stops when every residual is below this times the mechanism's size (lengths)."""

NEWTON_CLOSED_REL = 1e-9
"""A group is closed when its joint residual is at most this times the group's size."""

NEWTON_LEAST_STEP = 1e-6
"""Newton's damped step is shortened down to this fraction of the full step, no further."""


LOOP_SINGULAR_DET = 1e-10
"""A loop's linear system whose matrix, divided by its largest entry, has a determinant below this is
singular."""

SINGULAR_CONDITION = 1e12
"""Above this condition number the joint equations of a group are singular (a change point)."""

NEAR_SINGULAR_CONDITION = 1e8
"""Above this a row is near-singular (relative error about condition x u). A sound triad's
scaled joint equations have condition numbers near 1e4."""

PHASE_TOLERANCE = 1e-7
"""How far (relative to the radii) the construction's rolled arcs may be from the phase rule's."""

# --- the cross-check and its warnings (relative errors) -------------------------------------------

LOUD_ERROR = 1e-9
"""A construction that disagrees with the analytic solution by more than this is reported loudly."""

NEAR_SINGULAR_ERROR = 1e-9
"""An estimated relative error above this gets a ``near-singular`` warning."""

RIGID_REL_TOL = 1e-9
"""Given velocities (accelerations) of a rigid body may break rigidity by this much, relative."""

# --- what is printed ------------------------------------------------------------------------------

NOISE_REL = 1e-9
"""A value below this fraction of the largest value beside it (its column, its vector) is rounding noise
and printed as 0."""

PRINTED_ZERO = 5e-13
"""A handout prints a number smaller than this in magnitude (any unit) as 0."""

# --- lengths on the paper (mm) --------------------------------------------------------------------

PAPER_ROUNDING_MM = 1e-9
"""Lengths on the paper (mm) summed or scaled that exceed a bound by less than this still fit it."""

PAPER_EXACT_MM = 1e-12
"""Lengths on the paper (mm) computed two ways that differ by less than this are equal: a label's box
pushed exactly to its gap from what it names."""

PAPER_AREA_FLOOR_MM2 = 1e-12
"""The least span squared (mm^2) a polygon's image triangle is measured against: a triangle shrunk to a
point counts as flat."""

PAPER_SAME_MM = 1e-6
"""Two lengths or places on the paper this close (mm) are the same: a paper size, a panel's edge."""

FIT_MARGIN_REL = 1e-9
"""A scale that fits a drawing into its room is taken this much smaller (relative), so that rounding
cannot carry the drawing over the room's edge."""
