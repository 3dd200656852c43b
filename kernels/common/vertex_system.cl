/* The vertex-system gather of the vertex-block kernels (vbd.cl, jpgd.cl,
 * sosd.cl). The math is common/vertex_system.h, which the host VBD
 * reference (lib/solver/vbd/vbd_reference.cpp) compiles too. */
#include "common/vertex_system.h"
