/* SPDX-License-Identifier: MIT */
/* bench/speed/ceiling.c: what this machine's cores give a perfectly parallel
 * program, so the 1 -> 2 thread rows of bench/speed/run.sh can be read
 * against the machine, not only against the ideal 2x.
 *
 *   ceiling compute|memory|chase THREADS
 *
 * prints the seconds of a fixed amount of work split evenly over THREADS
 * threads (no shared data, no locks):
 *   compute  arithmetic in registers (a chain of multiplies and adds per
 *            thread): the cores alone
 *   memory   fresh memory, as the passes use it: every thread allocates its
 *            share of 256 MiB, writes every byte (page faults, zeroing,
 *            memory bandwidth) and frees it, four times
 *   chase    reads that wait on memory, as a walk of a large scene does:
 *            every thread follows its share of 12M links of one random
 *            cycle through 32 MiB (made before the clock starts, read only)
 * Built and run by run.sh (cc -O2 -pthread). */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define COMPUTE_STEPS 1600000000L /* multiply-adds in all */
#define MEMORY_BYTES (256L << 20)
#define MEMORY_ROUNDS 4
#define CHASE_STEPS 12000000L /* links followed in all */
#define CHASE_N (1L << 22)     /* longs in the cycle: 32 MiB */

static long *cycle; /* chase: cycle[i] is the next index after i */

struct share {
	int memory;     /* which workload: 0 compute, 1 memory, 2 chase */
	long amount;    /* this thread's steps or bytes */
	long start;     /* chase: where this thread's walk starts */
	double out;     /* keeps the work from being optimised away */
};

static void *run(void *arg)
{
	struct share *s = arg;
	if (s->memory == 2) {
		long at = s->start;
		for (long i = 0; i < s->amount; i++)
			at = cycle[at];
		s->out = (double)at + 1;
		return NULL;
	}
	if (!s->memory) {
		double a = 1.0, b = 0.5, c = 0.25, d = 0.125; /* four chains: the FMA units' latency hidden */
		for (long i = 0; i < s->amount / 4; i++) {
			a = a * 0.999999 + 1e-7;
			b = b * 0.999999 + 1e-7;
			c = c * 0.999999 + 1e-7;
			d = d * 0.999999 + 1e-7;
		}
		s->out = a + b + c + d;
		return NULL;
	}
	for (int r = 0; r < MEMORY_ROUNDS; r++) {
		unsigned char *p = malloc((size_t)s->amount);
		if (!p)
			return NULL;
		memset(p, r + 1, (size_t)s->amount);
		s->out += p[s->amount / 2];
		free(p);
	}
	return NULL;
}

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
	static const char *const kinds[] = {"compute", "memory", "chase"};
	int kind = -1, nt = argc == 3 ? atoi(argv[2]) : 0;
	for (int k = 0; k < 3 && argc == 3; k++)
		if (strcmp(argv[1], kinds[k]) == 0)
			kind = k;
	if (kind < 0 || nt < 1 || nt > 64) {
		fprintf(stderr, "usage: ceiling compute|memory|chase THREADS (1 to 64)\n");
		return 2;
	}
	if (kind == 2) { /* one cycle through every index (Sattolo's shuffle) */
		cycle = malloc(sizeof *cycle * (size_t)CHASE_N);
		if (!cycle) {
			fprintf(stderr, "ceiling: out of memory\n");
			return 1;
		}
		for (long i = 0; i < CHASE_N; i++)
			cycle[i] = i;
		unsigned long x = 88172645463325252ul;
		for (long i = CHASE_N - 1; i > 0; i--) {
			x ^= x << 13, x ^= x >> 7, x ^= x << 17;
			long j = (long)(x % (unsigned long)i), t = cycle[i];
			cycle[i] = cycle[j], cycle[j] = t;
		}
	}
	static const long amount[] = {COMPUTE_STEPS, MEMORY_BYTES, CHASE_STEPS};
	struct share s[64];
	pthread_t tid[64];
	double t0 = now(), sum = 0;
	for (int i = 0; i < nt; i++) {
		s[i] = (struct share){kind, amount[kind] / nt, CHASE_N / nt * i, 0};
		if (pthread_create(&tid[i], NULL, run, &s[i]) != 0) {
			fprintf(stderr, "ceiling: cannot start thread %d\n", i);
			return 1;
		}
	}
	for (int i = 0; i < nt; i++) {
		pthread_join(tid[i], NULL);
		sum += s[i].out;
	}
	printf("%.4f\n", now() - t0);
	free(cycle);
	return sum == 0 ? 1 : 0; /* (never 0: every share writes) */
}
