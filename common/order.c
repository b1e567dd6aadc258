/* SPDX-License-Identifier: MIT */
/* order.c: order statistics (order.h). */
#include "order.h"

static void swap(double *a, long i, long j)
{
	double t = a[i];
	a[i] = a[j];
	a[j] = t;
}

/* Heap sort of a[0..n): the fallback that keeps a bad run of pivots
 * O(n log n). */
static void sift(double *a, long i, long n)
{
	for (;;) {
		long c = 2 * i + 1;
		if (c >= n)
			return;
		if (c + 1 < n && a[c] < a[c + 1])
			c++;
		if (!(a[i] < a[c]))
			return;
		swap(a, i, c);
		i = c;
	}
}

static void heap_sort(double *a, long n)
{
	for (long i = n / 2 - 1; i >= 0; i--)
		sift(a, i, n);
	for (long e = n - 1; e > 0; e--) {
		swap(a, 0, e);
		sift(a, 0, e);
	}
}

double order_nth(double *a, long n, long k)
{
	long lo = 0, hi = n - 1, budget = 8;
	for (long m = n; m > 1; m >>= 1)
		budget += 2; /* 2 log2(n) rounds before the fallback */
	while (hi > lo) {
		if (budget-- == 0) {
			heap_sort(a + lo, hi - lo + 1);
			break;
		}
		/* the median of a[lo], a[mid], a[hi] as pivot, left at a[mid] */
		long mid = lo + (hi - lo) / 2;
		if (a[mid] < a[lo])
			swap(a, mid, lo);
		if (a[hi] < a[mid]) {
			swap(a, hi, mid);
			if (a[mid] < a[lo])
				swap(a, mid, lo);
		}
		double p = a[mid];
		/* Hoare's partition: a[lo..j] <= p <= a[i..hi], with j < i */
		long i = lo, j = hi;
		while (i <= j) {
			while (a[i] < p)
				i++;
			while (p < a[j])
				j--;
			if (i <= j)
				swap(a, i++, j--);
		}
		if (k <= j)
			hi = j;
		else if (k >= i)
			lo = i;
		else
			break; /* j < k < i: a[k] == p, in place */
	}
	return a[k];
}
