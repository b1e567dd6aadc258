/* SPDX-License-Identifier: MIT */
/* bench/speed/ceiling.c: what this machine's cores give a perfectly parallel
 * program, so the 1 -> 2 thread rows of bench/speed/run.sh can be read
 * against the machine, not only against the ideal 2x.
 *
 *   ceiling compute|memory THREADS
 *
 * prints the seconds of a fixed amount of work split evenly over THREADS
 * threads (no shared data, no locks):
 *   compute  arithmetic in registers (a chain of multiplies and adds per
 *            thread): the cores alone
 *   memory   fresh memory, as the passes use it: every thread allocates its
 *            share of 256 MiB, writes every byte (page faults, zeroing,
 *            memory bandwidth) and frees it, four times
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

struct share {
	int memory;     /* which workload */
	long amount;    /* this thread's steps or bytes */
	double out;     /* keeps the work from being optimised away */
};

static void *run(void *arg)
{
	struct share *s = arg;
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
	if (argc != 3 || (strcmp(argv[1], "compute") != 0 && strcmp(argv[1], "memory") != 0) || atoi(argv[2]) < 1 ||
	    atoi(argv[2]) > 64) {
		fprintf(stderr, "usage: ceiling compute|memory THREADS (1 to 64)\n");
		return 2;
	}
	int memory = strcmp(argv[1], "memory") == 0, nt = atoi(argv[2]);
	struct share s[64];
	pthread_t tid[64];
	double t0 = now(), sum = 0;
	for (int i = 0; i < nt; i++) {
		s[i] = (struct share){memory, (memory ? MEMORY_BYTES : COMPUTE_STEPS) / nt, 0};
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
	return sum == 0 ? 1 : 0; /* (never 0: every share writes) */
}
