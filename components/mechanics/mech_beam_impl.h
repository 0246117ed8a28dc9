/* Internal to the beam (not installed, nothing here is exported): what the chain builder
 * (mech_beam_chain.c) takes from the element (mech_beam.c). The checks are the element's own,
 * so that a chain refuses a section, or a length that makes its stiffness overflow, with the
 * same messages as a single element, and before it builds anything. */
#ifndef MECH_BEAM_IMPL_H
#define MECH_BEAM_IMPL_H

#include "mech_beam.h"

/* The AD scratch of an element's energy evaluations, reference counted: the elements of a chain
 * share one (they are evaluated one after another, so one scratch stays in cache). */
typedef struct beam_work beam_work;

/* A scratch holding one reference (the caller's); NULL when out of memory. */
beam_work *mech_beam_work_new_(void);
/* Drops one reference to a scratch (NULL: nothing); the last frees it. */
void mech_beam_work_release_(beam_work *w);

/* mech_beam with the scratch shared (shared gets one more reference; NULL: the element's own). */
int mech_beam_add_(bgr_model *m, bgr_comp c, const char *name, int node_a, int node_b,
                   const mech_section *sec, const double *E0, double L0, beam_work *shared);

/* BG_OK if sec obeys the rules of mech_beam.h, else the refusal naming the field (w: the
 * constructor, for the message). */
int mech_beam_bad_section_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                           const mech_section *sec);
/* BG_OK if the local stiffness of the section over the length L0 (and its damping beta K) is
 * finite, else the refusal. */
int mech_beam_bad_stiffness_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                             const mech_section *sec, double L0);

#endif
