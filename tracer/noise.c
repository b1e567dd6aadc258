/* SPDX-License-Identifier: MIT */
/* noise.c: POV-Ray 3.7's noise functions (docs/design.md §10).
 *
 * Generators 1 and 2 are Skinner's lattice noise after Perlin: each integer
 * lattice point hashes (through a 4096-entry permutation) to a row of a
 * table of 267 random numbers, which give a constant and three slopes; the
 * eight corners around p are blended with the cubic s-curve. Generator 2
 * rescales the result so that it fills [0,1]. Generator 3 is Perlin's
 * gradient noise over 2048 random unit vectors. The tables come from
 * POV-Ray's linear congruential generator (multiplier 1812433253, increment
 * 12345) and its 267-number table, so every value matches POV-Ray's. */
#include "noise.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>

/* ==== tables ============================================================== */

/* POV-Ray's 267 random numbers (the constant and slopes of each lattice
 * row overlap: row k uses entries k .. k+3 after interleaving, below). */
static const double rnums[267] = {
	-1, 0.604974, -0.937102, 0.414115, 0.576226, -0.0161593, 0.432334, 0.103685,
	0.590539, 0.0286412, 0.46981, -0.84622, -0.0734112, -0.304097, -0.40206, -0.210132,
	-0.919127, 0.652033, -0.83151, -0.183948, -0.671107, 0.852476, 0.043595, -0.404532,
	0.75494, -0.335653, 0.618433, 0.605707, 0.708583, -0.477195, 0.899474, 0.490623,
	0.221729, -0.400381, -0.853727, -0.932586, 0.659113, 0.961303, 0.325948, -0.750851,
	0.842466, 0.734401, -0.649866, 0.394491, -0.466056, -0.434073, 0.109026, 0.0847028,
	-0.738857, 0.241505, 0.16228, -0.71426, -0.883665, -0.150408, -0.90396, -0.686549,
	-0.785214, 0.488548, 0.0246433, 0.142473, -0.602136, 0.375845, -0.00779736, 0.498955,
	-0.268147, 0.856382, -0.386007, -0.596094, -0.867735, -0.570977, -0.914366, 0.28896,
	0.672206, -0.233783, 0.94815, 0.895262, 0.343252, -0.173388, -0.767971, -0.314748,
	0.824308, -0.342092, 0.721431, -0.24004, -0.63653, 0.553277, 0.376272, 0.158984,
	-0.452659, 0.396323, -0.420676, -0.454154, 0.122179, 0.295857, 0.0664225, -0.202075,
	-0.724788, 0.453513, 0.224567, -0.908812, 0.176349, -0.320516, -0.697139, 0.742702,
	-0.900786, 0.471489, -0.133532, 0.119127, -0.889769, -0.23183, -0.669673, -0.046891,
	-0.803433, -0.966735, 0.475578, -0.652644, 0.0112459, -0.730007, 0.128283, 0.145647,
	-0.619318, 0.272023, 0.392966, 0.646418, -0.0207675, -0.315908, 0.480797, 0.535668,
	-0.250172, -0.83093, -0.653773, -0.443809, 0.119982, -0.897642, 0.89453, 0.165789,
	0.633875, -0.886839, 0.930877, -0.537194, 0.587732, 0.722011, -0.209461, -0.0424659,
	-0.814267, -0.919432, 0.280262, -0.66302, -0.558099, -0.537469, -0.598779, 0.929656,
	-0.170794, -0.537163, 0.312581, 0.959442, 0.722652, 0.499931, 0.175616, -0.534874,
	-0.685115, 0.444999, 0.17171, 0.108202, -0.768704, -0.463828, 0.254231, 0.546014,
	0.869474, 0.875212, -0.944427, 0.130724, -0.110185, 0.312184, -0.33138, -0.629206,
	0.0606546, 0.722866, -0.0979477, 0.821561, 0.0931258, -0.972808, 0.0318151, -0.867033,
	-0.387228, 0.280995, -0.218189, -0.539178, -0.427359, -0.602075, 0.311971, 0.277974,
	0.773159, 0.592493, -0.0331884, -0.630854, -0.269947, 0.339132, 0.581079, 0.209461,
	-0.317433, -0.284993, 0.181323, 0.341634, 0.804959, -0.229572, -0.758907, -0.336721,
	0.605463, -0.991272, -0.0188754, -0.300191, 0.368307, -0.176135, -0.3832, -0.749569,
	0.62356, -0.573938, 0.278309, -0.971313, 0.839994, -0.830686, 0.439078, 0.66128,
	0.694514, 0.0565042, 0.54342, -0.438804, -0.0228428, -0.687068, 0.857267, 0.301991,
	-0.494255, -0.941039, 0.775509, 0.410575, -0.362081, -0.671534, -0.348379, 0.932433,
	0.886442, 0.868681, -0.225666, -0.062211, -0.0976425, -0.641444, -0.848112, 0.724697,
	0.473503, 0.998749, 0.174701, 0.559625, -0.029099, -0.337392, -0.958129, -0.659785,
	0.236042, -0.246937, 0.659449, -0.027512, 0.821897, -0.226215, 0.0181735, 0.500481,
	-0.420127, -0.427878, 0.566186};

#define GRAD_N 2048    /* Perlin gradients (a power of two) */
#define NRAND 32768    /* pattern random numbers */
#define NWAVES 256     /* wave sources made: number_of_waves at most */

static struct {
	double rt[2 * 267];           /* each number, then its half */
	unsigned short hash[8192];    /* a permutation of 0..4095, twice */
	int perm[2 * (GRAD_N + 1)];   /* Perlin's permutation, doubled */
	struct vec3 grad[2 * (GRAD_N + 1)]; /* Perlin's gradients, doubled */
	double rnd[NRAND];            /* MT19937 numbers in [0,1) */
	double sintab[1000];          /* sin(2πi/1000) */
	struct vec3 wave_src[NWAVES]; /* ripples and waves: sources */
	double wave_freq[NWAVES];     /* and their frequencies */
} T;

static pthread_once_t once = PTHREAD_ONCE_INIT;

/* POV-Ray's generator: the next state, and 15 bits of it. */
static uint32_t lcg(uint32_t *s)
{
	*s = *s * 1812433253u + 12345u;
	return (*s >> 16) & 0x7FFF;
}

/* The lattice permutation: 0..4095 shuffled from the top down. */
static void init_hash(void)
{
	uint32_t s = 0;
	for (int i = 0; i < 4096; i++)
		T.hash[i] = (unsigned short)i;
	for (int i = 4095; i >= 0; i--) {
		int j = (int)(lcg(&s) % 4096);
		unsigned short t = T.hash[i];
		T.hash[i] = T.hash[j];
		T.hash[j] = t;
	}
	for (int i = 0; i < 4096; i++)
		T.hash[4096 + i] = T.hash[i];
}

/* Perlin's tables: gradients drawn in the cube and kept when inside the
 * unit ball, then a permutation swapped on every other index (index
 * GRAD_N starts at 0, as POV-Ray's zeroed array does). */
static void init_perlin(void)
{
	uint32_t s = 1;
	for (int i = 0; i < GRAD_N; i++) {
		double v[3], l2;
		do {
			for (int j = 0; j < 3; j++)
				v[j] = (double)((int)(lcg(&s) % (GRAD_N << 1)) - GRAD_N) / GRAD_N;
			l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
		} while (l2 > 1.0 || l2 < 1.0e-5);
		double r = sqrt(l2);
		T.grad[i] = v3(v[0] / r, v[1] / r, v[2] / r);
	}
	for (int i = 0; i < GRAD_N; i++)
		T.perm[i] = i;
	for (int i = GRAD_N; i > 0; i -= 2) {
		int k = T.perm[i], j = (int)(lcg(&s) % GRAD_N);
		T.perm[i] = T.perm[j];
		T.perm[j] = k;
	}
	for (int i = 0; i < GRAD_N + 2; i++) {
		T.perm[GRAD_N + i] = T.perm[i];
		T.grad[GRAD_N + i] = T.grad[i];
	}
}

/* MT19937 with its default seed 5489; each number is one 32-bit draw over
 * 2^32, as Boost's uniform_real over mt19937 makes POV-Ray's table. */
static void init_rand(void)
{
	uint32_t mt[624];
	int idx = 624;
	mt[0] = 5489u;
	for (int i = 1; i < 624; i++)
		mt[i] = 1812433253u * (mt[i - 1] ^ (mt[i - 1] >> 30)) + (uint32_t)i;
	for (int n = 0; n < NRAND; n++) {
		if (idx >= 624) {
			for (int i = 0; i < 624; i++) {
				uint32_t y = (mt[i] & 0x80000000u) | (mt[(i + 1) % 624] & 0x7fffffffu);
				mt[i] = mt[(i + 397) % 624] ^ (y >> 1) ^ ((y & 1u) ? 0x9908b0dfu : 0u);
			}
			idx = 0;
		}
		uint32_t y = mt[idx++];
		y ^= y >> 11;
		y ^= (y << 7) & 0x9d2c5680u;
		y ^= (y << 15) & 0xefc60000u;
		y ^= y >> 18;
		T.rnd[n] = y / 4294967296.0;
	}
}

static struct vec3 dnoise(struct vec3 p);

static void init_waves(void)
{
	uint32_t s = (uint32_t)-560851967;
	for (int i = 0; i < NWAVES; i++) {
		T.wave_src[i] = v_norm(dnoise(v3(i, 0, 0)));
		T.wave_freq[i] = lcg(&s) * 0.000030518509476 + 0.01;
	}
}

static void init(void)
{
	for (int i = 0; i < 267; i++) {
		T.rt[2 * i] = rnums[i];
		T.rt[2 * i + 1] = rnums[i] * 0.5;
	}
	for (int i = 0; i < 1000; i++)
		T.sintab[i] = sin((double)i / 1000 * 2 * M_PI);
	init_hash();
	init_perlin();
	init_rand();
	init_waves(); /* uses noise_vec: the tables above are ready */
}

static void ready(void) { pthread_once(&once, init); }

/* ==== lattice noise (generators 1 and 2) ================================= */

/* One axis of p on the lattice: the hash index of the cell below, and the
 * offset from it (POV-Ray's rounding of negative coordinates, 1e-10 short
 * of a whole step, kept). */
static int cell(double x, double *frac)
{
	int t = x >= 0 ? (int)x : (int)(x - (1 - 1.0e-10));
	*frac = x - t;
	return (t + 10000) & 0xFFF;
}

static int hash2(int a, int b) { return T.hash[T.hash[a] ^ b]; }

/* The table row of lattice column h at height z. */
static const double *row(int h, int z) { return &T.rt[(T.hash[h ^ z] & 0xFF) * 2]; }

/* One corner's term: weight s times the row's constant and slopes. */
static double term(const double *m, double s, double x, double y, double z)
{
	return s * (m[1] + m[2] * x + m[4] * y + m[6] * z);
}

/* The eight corners around p: their hash columns and weights, the offsets. */
struct lattice {
	int h[4], iz;          /* columns (x0y0, x1y0, x0y1, x1y1); z cell */
	double w[8];           /* weights: four at z0, four at z1 */
	double fx, fy, fz;     /* offsets from the lower corner */
};

static void lattice(struct vec3 p, struct lattice *L)
{
	int ix = cell(p.x, &L->fx), iy = cell(p.y, &L->fy);
	L->iz = cell(p.z, &L->fz);
	double sx = L->fx * L->fx * (3 - 2 * L->fx), sy = L->fy * L->fy * (3 - 2 * L->fy);
	double sz = L->fz * L->fz * (3 - 2 * L->fz), tx = 1 - sx, ty = 1 - sy, tz = 1 - sz;
	L->h[0] = hash2(ix, iy), L->h[1] = hash2(ix + 1, iy);
	L->h[2] = hash2(ix, iy + 1), L->h[3] = hash2(ix + 1, iy + 1);
	double wxy[4] = {tx * ty, sx * ty, tx * sy, sx * sy};
	for (int k = 0; k < 4; k++) {
		L->w[k] = wxy[k] * tz;
		L->w[4 + k] = wxy[k] * sz;
	}
}

static double lattice_noise(struct vec3 p, int gen)
{
	struct lattice L;
	lattice(p, &L);
	double sum = 0;
	for (int c = 0; c < 8; c++) {
		int k = c & 3, up = c >> 2;
		double x = (k & 1) ? L.fx - 1 : L.fx, y = (k & 2) ? L.fy - 1 : L.fy, z = up ? L.fz - 1 : L.fz;
		sum += term(row(L.h[k], L.iz + up), L.w[c], x, y, z);
	}
	if (gen == 2) /* the measured range −1.05242 … 0.988997 stretched to [0,1] */
		sum = (sum + 1.05242) * 0.48985582;
	else
		sum += 0.5;
	return sum < 0 ? 0 : sum > 1 ? 1 : sum;
}

/* POV-Ray's DNoise, without the table check (init_waves runs it). */
static struct vec3 dnoise(struct vec3 p)
{
	struct lattice L;
	lattice(p, &L);
	/* POV-Ray's order of the corners, for the same rounding */
	static const int order[8] = {0, 1, 3, 2, 6, 7, 5, 4};
	double r[3] = {0, 0, 0};
	for (int i = 0; i < 8; i++) {
		int c = order[i], k = c & 3, up = c >> 2;
		double x = (k & 1) ? L.fx - 1 : L.fx, y = (k & 2) ? L.fy - 1 : L.fy, z = up ? L.fz - 1 : L.fz;
		const double *m = row(L.h[k], L.iz + up);
		for (int a = 0; a < 3; a++)
			r[a] += term(m + 8 * a, L.w[c], x, y, z);
	}
	return v3(r[0], r[1], r[2]);
}

struct vec3 noise_vec(struct vec3 p)
{
	ready();
	return dnoise(p);
}

/* ==== Perlin's gradient noise (generator 3) ============================== */

static void perlin_axis(double v, int *b0, int *b1, double *r0)
{
	double t = v + 10000000.023157213;
	int it = (int)floor(t);
	*b0 = it & (GRAD_N - 1);
	*b1 = (*b0 + 1) & (GRAD_N - 1);
	*r0 = t - it;
}

static double lerp(double t, double a, double b) { return a + t * (b - a); }

static double perlin(struct vec3 p)
{
	int bx0, bx1, by0, by1, bz0, bz1;
	double rx, ry, rz;
	perlin_axis(p.x, &bx0, &bx1, &rx);
	perlin_axis(p.y, &by0, &by1, &ry);
	perlin_axis(p.z, &bz0, &bz1, &rz);
	int i = T.perm[bx0], j = T.perm[bx1];
	int b[4] = {T.perm[i + by0], T.perm[j + by0], T.perm[i + by1], T.perm[j + by1]};
	double sx = rx * rx * (3 - 2 * rx), sy = ry * ry * (3 - 2 * ry), sz = rz * rz * (3 - 2 * rz);
	double layer[2];
	for (int up = 0; up < 2; up++) {
		int bz = up ? bz1 : bz0;
		double z = up ? rz - 1 : rz, v[4];
		for (int k = 0; k < 4; k++) {
			struct vec3 g = T.grad[b[k] + bz];
			v[k] = g.x * ((k & 1) ? rx - 1 : rx) + g.y * ((k & 2) ? ry - 1 : ry) + g.z * z;
		}
		layer[up] = lerp(sy, lerp(sx, v[0], v[1]), lerp(sx, v[2], v[3]));
	}
	return lerp(sz, layer[0], layer[1]);
}

/* ==== the public functions =============================================== */

double noise_at(struct vec3 p, int gen)
{
	ready();
	if (gen == 3) { /* POV-Ray's correction of the gradient noise's bias */
		double s = 0.5 * (1.59 * perlin(p) + 0.985);
		return s < 0 ? 0 : s > 1 ? 1 : s;
	}
	return lattice_noise(p, gen);
}

double noise_turb(struct vec3 p, const struct turb_params *t, int gen)
{
	double v = noise_at(p, gen);
	if (gen > 1)
		v = fmin(fmax(2 * v - 0.5, 0), 1);
	double l = t->lambda, o = t->omega;
	for (int i = 2; i <= t->octaves; i++) {
		double n = noise_at(v_scale(p, l), gen);
		v += o * (gen > 1 ? 2 * n - 0.5 : n); /* unclipped, as in POV-Ray */
		if (i < t->octaves) {
			l *= t->lambda;
			o *= t->omega;
		}
	}
	return v;
}

struct vec3 noise_dturb(struct vec3 p, const struct turb_params *t)
{
	struct vec3 r = noise_vec(p);
	double l = t->lambda, o = t->omega;
	for (int i = 2; i <= t->octaves; i++) {
		r = v_madd(r, noise_vec(v_scale(p, l)), o);
		if (i < t->octaves) {
			l *= t->lambda;
			o *= t->omega;
		}
	}
	return r;
}

double noise_rand(unsigned long k)
{
	ready();
	return T.rnd[k % NRAND];
}

int noise_hash3(int x, int y, int z)
{
	ready();
	return T.hash[T.hash[T.hash[x & 0xFFF] ^ (y & 0xFFF)] ^ (z & 0xFFF)];
}

struct vec3 noise_wave_source(int n)
{
	ready();
	return T.wave_src[n % NWAVES];
}

double noise_wave_freq(int n)
{
	ready();
	return T.wave_freq[n % NWAVES];
}

double noise_cycloidal(double v)
{
	ready();
	int i = v >= 0 ? (int)((v - floor(v)) * 1000) : (int)(-(v + floor(-v)) * 1000);
	i = i < 0 ? 0 : i > 999 ? 999 : i; /* guards against rounding, and NaN's cast */
	return v >= 0 ? T.sintab[i] : -T.sintab[i];
}

double noise_triangle(double v)
{
	double t = v >= 0 ? v - floor(v) : v - (-1 - floor(fabs(v)));
	return t >= 0.5 ? 2 * (1 - t) : 2 * t;
}
