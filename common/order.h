/* SPDX-License-Identifier: MIT */
/* order.h: order statistics without a full sort. */
#ifndef ARVO_ORDER_H
#define ARVO_ORDER_H

/* The k-th smallest of a[0..n) (0 <= k < n), the value a sort would put at
 * a[k]: a[] is reordered so that a[k] holds it, a[0..k) nothing greater and
 * a(k..n) nothing smaller. Expected O(n) (quickselect, median-of-three
 * pivots; a heap sort of what is left bounds the worst case). NaNs compare
 * equal to everything, as under qsort with a < and > comparison. */
double order_nth(double *a, long n, long k);

#endif
