/* SPDX-License-Identifier: MIT */
/* env.c: identifier scopes (POV-Ray's dynamic scoping: a stack of tables)
 * and the macro table. #declare writes to the innermost scope that already
 * holds the name, else to the global scope; #local writes to the innermost. */
#include <string.h>

#include "internal.h"

struct entry {
	const char *name;         /* key (arena) */
	uint32_t hash;            /* hash(name) */
	struct value val;         /* identifier value */
	const struct node *macro; /* N_MACRO when this is a macro */
	struct entry *next;       /* chain */
};

struct scope {
	struct entry **buckets; /* hash chains */
	int nbuckets;           /* power of two */
	int count;              /* entries */
	struct scope *next;     /* on E->spare_scopes once released */
};

static uint32_t hash(const char *s)
{
	uint32_t h = 2166136261u;
	for (; *s; s++)
		h = (h ^ (unsigned char)*s) * 16777619u;
	return h;
}

struct scope *scope_new(struct eval *E)
{
	struct scope *sc = E->spare_scopes;
	if (sc) { /* a released scope: its table and entries are reused */
		E->spare_scopes = sc->next;
		sc->next = NULL;
		return sc;
	}
	sc = ARENA_NEW(&E->arena, struct scope);
	sc->nbuckets = 16;
	sc->buckets = ARENA_ARRAY(&E->arena, struct entry *, sc->nbuckets);
	return sc;
}

/* A macro's or an include's scope, popped and no longer reachable: its
 * entries go to E->spare_entries and the table to E->spare_scopes, so a
 * million macro calls cost no more memory than the deepest of them. */
void scope_release(struct eval *E, struct scope *sc)
{
	for (int i = 0; i < sc->nbuckets; i++) {
		for (struct entry *e = sc->buckets[i], *next; e; e = next) {
			next = e->next;
			e->next = E->spare_entries;
			E->spare_entries = e;
		}
		sc->buckets[i] = NULL;
	}
	sc->count = 0;
	sc->next = E->spare_scopes;
	E->spare_scopes = sc;
	E->env_gen++;
}

void scope_push(struct eval *E, struct scope *sc, struct srcloc loc)
{
	if (E->nscopes >= MAX_SCOPES)
		eval_fail(E, loc, "too many nested scopes (more than %d)", MAX_SCOPES);
	E->scopes[E->nscopes++] = sc;
	E->env_gen++;
}

void scope_pop(struct eval *E)
{
	E->nscopes--;
	E->env_gen++;
}

/* strcmp(a, b) == 0 for the short names of scenes, without a call. */
static inline bool same(const char *a, const char *b)
{
	while (*a && *a == *b)
		a++, b++;
	return *a == *b;
}

static struct entry *find_h(struct scope *sc, const char *name, uint32_t h)
{
	for (struct entry *e = sc->buckets[h & (uint32_t)(sc->nbuckets - 1)]; e; e = e->next)
		if (e->hash == h && same(e->name, name))
			return e;
	return NULL;
}

static struct entry *find(struct scope *sc, const char *name)
{
	return find_h(sc, name, hash(name));
}

/* Doubles a scope's table when it gets crowded. */
static void grow(struct eval *E, struct scope *sc)
{
	int nb = sc->nbuckets * 2;
	struct entry **b = ARENA_ARRAY(&E->arena, struct entry *, nb);
	for (int i = 0; i < sc->nbuckets; i++) {
		for (struct entry *e = sc->buckets[i], *next; e; e = next) {
			next = e->next;
			uint32_t h = e->hash & (uint32_t)(nb - 1);
			e->next = b[h];
			b[h] = e;
		}
	}
	sc->buckets = b;
	sc->nbuckets = nb;
}

static struct entry *insert(struct eval *E, struct scope *sc, const char *name)
{
	struct entry *e = find(sc, name);
	if (e) {
		if (e->macro) { /* a macro becomes a variable: lookups change */
			e->macro = NULL;
			E->env_gen++;
		}
		return e;
	}
	E->env_gen++;
	if (sc->count >= sc->nbuckets)
		grow(E, sc);
	e = E->spare_entries;
	if (e) {
		E->spare_entries = e->next;
		memset(e, 0, sizeof *e);
	} else {
		e = ARENA_NEW(&E->arena, struct entry);
	}
	e->name = name; /* names are AST or evaluator strings: they live as long */
	e->hash = hash(name);
	uint32_t h = e->hash & (uint32_t)(sc->nbuckets - 1);
	e->next = sc->buckets[h];
	sc->buckets[h] = e;
	sc->count++;
	return e;
}

struct value *env_lookup(struct eval *E, const char *name)
{
	uint32_t h = hash(name);
	for (int i = E->nscopes - 1; i >= 0; i--) {
		struct entry *e = find_h(E->scopes[i], name, h);
		if (e && !e->macro)
			return &e->val;
	}
	return NULL;
}

const struct node *env_macro(struct eval *E, const char *name)
{
	for (int i = E->nscopes - 1; i >= 0; i--) {
		struct entry *e = find(E->scopes[i], name);
		if (e)
			return e->macro;
	}
	return NULL;
}

struct value *env_declare(struct eval *E, const char *name, bool local)
{
	struct scope *sc = E->scopes[local ? E->nscopes - 1 : 0];
	if (!local) {
		uint32_t h = hash(name);
		for (int i = E->nscopes - 1; i > 0; i--) {
			struct entry *e = find_h(E->scopes[i], name, h);
			if (e && !e->macro)
				return &e->val;
		}
	}
	return &insert(E, sc, name)->val;
}

void env_define_macro(struct eval *E, const char *name, const struct node *def)
{
	struct entry *e = insert(E, E->scopes[0], name);
	e->macro = def;
	E->env_gen++;
	e->val = val_none();
}

bool env_undef(struct eval *E, const char *name)
{
	for (int i = E->nscopes - 1; i >= 0; i--) {
		struct scope *sc = E->scopes[i];
		struct entry **pp = &sc->buckets[hash(name) & (uint32_t)(sc->nbuckets - 1)];
		for (; *pp; pp = &(*pp)->next) {
			if (strcmp((*pp)->name, name) == 0) {
				*pp = (*pp)->next;
				sc->count--;
				E->env_gen++;
				return true;
			}
		}
	}
	return false;
}

/* ==== memos ============================================================== */

/* An identifier, a call or a #declare resolves its name to the same entry
 * as long as no scope was pushed, popped or recycled and no name was added,
 * removed or turned from a macro into a variable: E->env_gen counts those
 * changes, and a node keeps what its name resolved to with the count it was
 * found at (a loop body's names are looked up once, not once per pass). */

/* env_lookup_node and env_declare_node (internal.h) when the memo is stale. */
struct value *env_lookup_again(struct eval *E, const struct node *n)
{
	struct node *w = (struct node *)n;
	w->memo = env_lookup(E, n->str);
	w->memo_gen = E->env_gen;
	return w->memo;
}

struct value *env_declare_again(struct eval *E, const struct node *n, bool local)
{
	struct node *w = (struct node *)n;
	w->memo = env_declare(E, n->str, local);
	w->memo_gen = E->env_gen; /* after the insert's own change */
	return w->memo;
}

struct call_memo {
	const struct node *macro;
	struct value *var;
	const struct builtin *builtin; /* the built-in of that name, once found */
	double (*float_fn)(double);    /* and builtin_float_fn of it */
	bool builtin_found;            /* builtin was looked up (it stays valid) */
};

static struct call_memo *call_memo(struct eval *E, const struct node *n)
{
	struct node *w = (struct node *)n;
	if (!w->memo) {
		w->memo = ARENA_NEW(&E->arena, struct call_memo);
		w->memo_gen = 0; /* env_gen starts at 1: the names are looked up */
	}
	return w->memo;
}

/* The memo m of a call of name, with its built-in looked up. */
static struct call_memo *with_builtin(struct call_memo *m, const char *name)
{
	if (!m->builtin_found) {
		m->builtin = builtin_find(name);
		m->float_fn = builtin_float_fn(m->builtin);
		m->builtin_found = true;
	}
	return m;
}

const struct builtin *env_call_builtin(struct eval *E, const struct node *n)
{
	return with_builtin(call_memo(E, n), n->str)->builtin;
}

const struct node *env_call_lookup(struct eval *E, const struct node *n, struct value **var)
{
	struct node *w = (struct node *)n;
	struct call_memo *m = call_memo(E, n);
	if (w->memo_gen != E->env_gen) {
		m->macro = env_macro(E, n->str);
		m->var = m->macro ? NULL : env_lookup(E, n->str);
		w->memo_gen = E->env_gen;
	}
	*var = m->var;
	return m->macro;
}

double (*env_call_float_fn(struct eval *E, const struct node *n))(double)
{
	struct value *var;
	if (env_call_lookup(E, n, &var) || (var && var->kind == V_FUNCTION))
		return NULL;
	return with_builtin(n->memo, n->str)->float_fn;
}
