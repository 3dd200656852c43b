/* solver.ordering: batches (graph/simd_batches): the lanes of one batch of
 * an XPBD element set, shared by the kernels and the plan that pads the set
 * to whole batches. 8 = the floats of an AVX2 register. */
#ifndef ATS_XPBD_BATCHES_H
#define ATS_XPBD_BATCHES_H
#define ATS_XPBD_BATCH_WIDTH 8
#endif
