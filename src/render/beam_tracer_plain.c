/* The beam tracer once more, without the hybrid walks, for views whose BVH
 * has no hand-over points (see render/beam_tracer.c). Compiled once per
 * ISA. */
#define BEAM_PLAIN 1
#include "render/beam_tracer.c"
