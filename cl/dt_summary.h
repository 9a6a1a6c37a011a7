/* summarize_wide.cl's partial results, shared with the host that sizes their buffer: DT_PARTIAL_FIELDS
 * floats per work-group, field f of group g at partials[f * groups + g]. */
#ifndef DT_SUMMARY_H
#define DT_SUMMARY_H
#define DT_PARTIAL_MAX 0    /* largest log weight */
#define DT_PARTIAL_ARGMAX 1 /* its particle (the first holding it), as a float's bits */
#define DT_PARTIAL_MAX_LL 2 /* largest log-likelihood */
#define DT_PARTIAL_SUM 3    /* sum of exp(log weight - the largest) */
#define DT_PARTIAL_ACC 4    /* 12 weighted sums, as summarize.cl's acc */
#define DT_PARTIAL_STEP 16  /* 4 Karcher steps x 3 */
#define DT_KARCHER_STEPS 4
#define DT_PARTIAL_FIELDS 28
#endif
