/* SPDX-License-Identifier: MIT */
/* paths.c: which files a scene may read (docs/design.md §9, "Files").
 *
 * A scene reads only below its roots: the scene file's directory, the -I
 * directories, the standard library, POV-Ray's include directory and the
 * --allow-read directories.
 * A name the scene gives (#include, image_map) is joined to each directory
 * searched, made absolute and normalized lexically ("." and ".." removed
 * from the text, no symlinks resolved); the result must lie below a root,
 * else it is refused without being looked at. So an absolute name or a ".."
 * can never leave the roots, while a symlink a user placed inside a root
 * may point anywhere. The file opened is the normalized path, so "link/.."
 * means the root again, not the parent of the link's target. */
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "internal.h"

/* Writes the absolute, lexically normalized form of dir/name (name alone
 * when it is absolute; dir may be NULL) into out. Returns 0, or -1 when it
 * does not fit. */
static int normalize(const char *dir, const char *name, char *out, size_t size)
{
	char buf[PATH_MAX * 3];
	size_t n = 0;
	if (name[0] == '/') {
		n = (size_t)snprintf(buf, sizeof buf, "%s", name);
	} else {
		char cwd[PATH_MAX];
		if (dir && dir[0] == '/')
			n = (size_t)snprintf(buf, sizeof buf, "%s/%s", dir, name);
		else if (getcwd(cwd, sizeof cwd))
			n = (size_t)snprintf(buf, sizeof buf, "%s/%s/%s", cwd, dir ? dir : ".", name);
		else
			return -1;
	}
	if (n >= sizeof buf || size < 2)
		return -1;
	/* copy component by component: skip "" and ".", ".." drops the last */
	size_t len = 0;
	for (char *p = buf, *next; *p; p = next) {
		while (*p == '/')
			p++;
		next = p;
		while (*next && *next != '/')
			next++;
		size_t cl = (size_t)(next - p);
		if (cl == 0 || (cl == 1 && p[0] == '.'))
			continue;
		if (cl == 2 && p[0] == '.' && p[1] == '.') { /* back to the previous '/' ("/.." is "/") */
			while (len > 0 && out[--len] != '/')
				;
			continue;
		}
		if (len + 1 + cl + 1 > size)
			return -1;
		out[len++] = '/';
		memcpy(out + len, p, cl);
		len += cl;
		out[len] = '\0';
	}
	if (len == 0)
		out[len++] = '/';
	out[len] = '\0';
	return 0;
}

/* Is path (normalized) the directory root or below it? */
static int below(const char *root, const char *path)
{
	size_t n = strlen(root);
	if (n == 1)
		return 1; /* "/" */
	return strncmp(root, path, n) == 0 && (path[n] == '/' || path[n] == '\0');
}

/* Is the normalized path below one of the scene's roots? */
static int readable(struct eval *E, const char *path)
{
	char root[PATH_MAX];
	const struct eval_options *o = E->opt;
	if (normalize(NULL, E->dir_stack[0], root, sizeof root) == 0 && below(root, path))
		return 1;
	for (int i = 0; i < o->ninclude; i++)
		if (normalize(NULL, o->include_dirs[i], root, sizeof root) == 0 && below(root, path))
			return 1;
	if (o->stdlib_dir && normalize(NULL, o->stdlib_dir, root, sizeof root) == 0 && below(root, path))
		return 1;
	if (o->pov_include_dir && normalize(NULL, o->pov_include_dir, root, sizeof root) == 0 && below(root, path))
		return 1;
	for (int i = 0; i < o->nallow; i++)
		if (normalize(NULL, o->allow_read[i], root, sizeof root) == 0 && below(root, path))
			return 1;
	return 0;
}

/* Finds a file the scene names (#include, image_map): in the directory of
 * the file being read, then each -I directory, then the standard library,
 * then POV-Ray's include directory (an absolute name is looked for as it
 * is). A library file that includes its own name reads the next file of
 * that name on the path (as C's #include_next): arvo's glass.inc adds
 * POV-Ray's. Returns a malloc'd real path, and in *found_dir (if not NULL)
 * the directory, as given, where it was found. `what` names the file kind
 * in errors. A name that would lead outside the roots from every directory
 * searched is refused (exit 65); one that is found nowhere sets E->missing
 * (exit 66). */
static char *find_file(struct eval *E, const char *name, struct srcloc loc, const char **found_dir,
                       int *refused_out, int *tried_out)
{
	const char *dirs[68];
	int nd = 0;
	dirs[nd++] = E->dir_stack[E->include_depth];
	char libreal[PATH_MAX] = "", self[PATH_MAX] = "";
	if (name[0] != '/') {
		for (int i = 0; i < E->opt->ninclude && nd < 64; i++)
			dirs[nd++] = E->opt->include_dirs[i];
		if (E->opt->stdlib_dir && !realpath(dirs[nd++] = E->opt->stdlib_dir, libreal))
			libreal[0] = '\0';
		if (E->opt->pov_include_dir)
			dirs[nd++] = E->opt->pov_include_dir;
	}
	const struct srcfile *from = srcfile_get(loc.file);
	if (!from || !realpath(from->name, self))
		self[0] = '\0';
	int refused = 0, tried = 0;
	for (int i = 0; i < nd; i++) {
		char cand[PATH_MAX], real[PATH_MAX];
		struct stat sb;
		if (normalize(dirs[i], name, cand, sizeof cand) != 0)
			continue;
		tried++;
		if (!readable(E, cand)) {
			refused++; /* not even looked at: a scene may not probe outside */
			continue;
		}
		char realdir[PATH_MAX];
		if (stat(cand, &sb) != 0 || S_ISDIR(sb.st_mode) || !realpath(cand, real))
			continue;
		if (self[0] && strcmp(real, self) == 0 && libreal[0] && realpath(dirs[i], realdir) &&
		    strcmp(realdir, libreal) == 0)
			continue; /* the library file naming itself: the next one on the path */
		if (found_dir)
			*found_dir = name[0] == '/' ? "/" : dirs[i];
		return mem_strdup(real);
	}
	*refused_out = refused;
	*tried_out = tried;
	return NULL;
}

char *eval_try_file(struct eval *E, const char *name, struct srcloc loc)
{
	int refused, tried;
	return name[0] ? find_file(E, name, loc, NULL, &refused, &tried) : NULL;
}

char *eval_find_file(struct eval *E, const char *name, struct srcloc loc, const char *what, const char **found_dir)
{
	int refused, tried;
	if (name[0] == '\0')
		eval_fail(E, loc, "%s name is empty", what);
	char *real = find_file(E, name, loc, found_dir, &refused, &tried);
	if (real)
		return real;
	if (refused > 0 && refused == tried)
		eval_fail(E, loc, "%s '%s' is outside the directories this scene may read (its own, -I "
		          "directories and the library); --allow-read DIR grants more", what, name);
	E->missing = 1;
	eval_fail(E, loc, "cannot find %s '%s'", what, name);
}
