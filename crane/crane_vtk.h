/* The crane's motion as a ParaView time series (crane --vtk): a collection DIR/crane.pvd that
 * lists one VTK XML PolyData file per frame, DIR/vtk/frame_NNNNN.vtp (ASCII), with the frame's
 * time as its timestep. Open crane.pvd in ParaView and press play.
 *
 * Frames: global frame, Z0 up, origin as in the scene (the slewing joint A on the axis Z0, the
 * platform frame coinciding with the global one at theta = 0); SI units throughout (m, kg, s, N,
 * N m, Pa). Each .vtp is one piece of polydata.
 * Part codes (Int32, points and cells): 0 platform, 1 boom, 2 gantry, 3 load, 4 counterweight,
 * 5 ties, 6 rope, 7 foot.
 *   points   the deck outline's four corners and the points below the gantry in the deck's plane
 *            (part 0), the boom's nodes from the foot (node 0) to the tip (part 1), the gantry
 *            top or the ties' two upper ends (part 2), the load (3), the counterweight (4);
 *   verts    the foot (7, on boom node 0), the gantry point(s) (2), the load (3), the
 *            counterweight (4);
 *   lines    the deck outline (closed), the gantry mast(s) and the bar between two gantry
 *            points (0), the boom as one polyline through its nodes (1), each tie from its
 *            upper end to the tip (5), the rope from the tip to the load (6).
 * Point data (a value for every point, 0 where it does not apply):
 *   part           the part code, node  the boom node's index (Int32, -1 elsewhere),
 *   mass [kg]      of the load and the counterweight (the point masses; the boom's lumped
 *                  node masses are not listed),
 *   deflection [m] the node's displacement from its start position carried round by the
 *                  platform's angle (crane_geom, crane_model.h: the elastic motion with the rigid
 *                  slewing removed), global; deflection_luff and deflection_side [m] its
 *                  components in and out of the luffing plane (tip_defl_1/2 at the tip);
 *   section_force [N], section_moment [N m]  (beam booms only) what the boom's tip side exerts
 *                  on its foot side at the node, global; section_force_local = (N, Q_luff,
 *                  Q_side), section_moment_local = (M_torsion, M_about_b2, M_about_b3): along
 *                  the boom (tension > 0), its normal in the luffing plane, sideways.
 * Cell data: part, tension [N] (ties and rope, 0 elsewhere).
 * Field data: TimeValue [s], theta [rad], omega [rad/s], rope_tension [N] (with a rope),
 * tie_tension [N] (one tuple per tie), pump_x [-], p_high and p_low [Pa] (with hydraulics).
 * Array names carry no units; the units are the ones stated here. */
#ifndef CRANE_VTK_H
#define CRANE_VTK_H

#include <stddef.h>

#include "crane_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct crane_vtk crane_vtk;

/* Starts the series in dir (which exists): creates dir/vtk/ and dir/crane.pvd. NULL with the
 * reason in msg (size bytes) if a file cannot be written or out of memory. */
crane_vtk *crane_vtk_open(const char *dir, const char *scene_name, char *msg, size_t size);
/* Writes the next frame from g and lists it in the collection. 0, or -1 if it could not be
 * written (the reason in msg). */
int crane_vtk_frame(crane_vtk *v, const crane_geom *g, char *msg, size_t size);
/* Completes crane.pvd and frees v; the number of frames written, or -1 if the collection could
 * not be completed. */
int crane_vtk_close(crane_vtk **v);

#ifdef __cplusplus
}
#endif
#endif
