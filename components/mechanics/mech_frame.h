/* Private (not installed): the kinds of the mechanical unknowns under a co-moving frame's
 * rigid motion (bgr_declare_frame, bgr_model.h; bgr_frame_rotation, bgr_analysis.h). Every
 * port quantity of the mechanical components is a global vector (mech_body.h: force, moment,
 * velocity, angular velocity); positions (a body's or point mass's x) are points; a body's
 * orientation is a quaternion body to global; a body's angular velocity w is in its own frame
 * and an axial member's d is a global vector. */
#ifndef MECH_FRAME_H
#define MECH_FRAME_H

#include "bgr_model.h"

/* The global vectors of every 3D or 6D port of el (efforts and flows; 1D ports carry scalars:
 * nothing). BG_OK or bgr_declare_frame's status. */
int mech_frame_ports(bgr_element *el, bgr_model *m);
/* kind (BGR_FRAME_*) for the 3 (4: quaternion) consecutive unknowns from var. */
int mech_frame_group(bgr_element *el, bgr_model *m, int kind, int var);

#endif
