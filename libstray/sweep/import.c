/*
 * import.c - `stray sweep import` (sweep_import.h): the files given and
 * the log's rows matched by file name, every frame's header checked
 * against its row (import_check.c) and all mismatches reported before
 * anything is written; then each frame, in the log's order (the order of
 * acquisition, which the reduction's visits and drift follow), written
 * as our own frame with the same pixels, its original copied byte for
 * byte under original/, and import.csv tying the two.  The folder is
 * filled as a temporary and renamed into place only when all is done.
 */
#define _DEFAULT_SOURCE		/* lstat, fsync */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "import_priv.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define PATH_LEN STRAY_IMPORT_PATH_LEN
#define input stray_import_input

struct state {
	const struct stray_import_opts *o;
	struct stray_import_log log;
	struct input *in;
	size_t n_in, cap_in;
	struct input **of_row;		/* each log row's file, or NULL */
	double *rb;			/* each row's read-back, or NAN */
	long *seq;			/* each row's SEQNUM */
	struct stray_import_check chk;
	struct stray_import_header first;
	const char *first_path;
	struct stray_sweep_buf buf;
};

static int add_input(struct state *s, const char *dir, const char *name,
		     struct stray_error *err)
{
	struct input *p;
	int n;

	if (s->n_in == s->cap_in) {
		size_t cap = s->cap_in ? 2 * s->cap_in : 64;

		if (s->n_in >= STRAY_IMPORT_ROWS_MAX)
			return stray_error_at(err, STRAY_EINVAL, dir ? dir :
				name, 0, "file", "more than 100000 frames");
		if (!(p = realloc(s->in, cap * sizeof(*p))))
			return stray_error_at(err, STRAY_ENOMEM, name, 0, 0, 0);
		s->in = p;
		s->cap_in = cap;
	}
	p = &s->in[s->n_in];
	memset(p, 0, sizeof(*p));
	n = dir ? snprintf(p->path, sizeof(p->path), "%s/%s", dir, name)
		: snprintf(p->path, sizeof(p->path), "%s", name);
	if (n < 0 || (size_t)n >= sizeof(p->path))
		return stray_error_at(err, STRAY_EINVAL, name, 0, "path",
				      "too long");
	s->n_in++;
	return STRAY_OK;
}

static int frame_name(const char *name)
{
	static const char *const ext[] = { ".fits", ".fit", ".fts", ".tif",
					   ".tiff", NULL };
	size_t n = strlen(name), k;

	for (k = 0; ext[k]; k++)
		if (n > strlen(ext[k]) &&
		    strcasecmp(name + n - strlen(ext[k]), ext[k]) == 0)
			return name[0] != '.';
	return 0;
}

static int by_name(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

/* A folder's frame files (FITS and TIFF by their extension, not hidden)
 * in name order. */
static int add_dir(struct state *s, const char *dir, struct stray_error *err)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	char **names = NULL;
	size_t n = 0, cap = 0, i;
	int rc = STRAY_OK;

	if (!d)
		return stray_error_at(err, STRAY_EIO, dir, 0, "folder",
				      "cannot be listed");
	while (rc == STRAY_OK && (e = readdir(d)) != NULL) {
		if (!frame_name(e->d_name))
			continue;
		if (n == cap) {
			char **p = realloc(names, (cap = cap ? 2 * cap : 64) *
					   sizeof(*p));

			if (!p) {
				rc = stray_error_at(err, STRAY_ENOMEM, dir, 0,
						    0, 0);
				break;
			}
			names = p;
		}
		if (n >= STRAY_IMPORT_ROWS_MAX)
			rc = stray_error_at(err, STRAY_EINVAL, dir, 0, "folder",
					    "more than 100000 frames");
		else if (!(names[n++] = strdup(e->d_name)))
			rc = stray_error_at(err, STRAY_ENOMEM, dir, 0, 0, 0);
	}
	closedir(d);
	if (rc == STRAY_OK && n > 0)
		qsort(names, n, sizeof(*names), by_name);
	for (i = 0; i < n; i++) {
		if (rc == STRAY_OK && names[i])
			rc = add_input(s, dir, names[i], err);
		free(names[i]);
	}
	free(names);
	return rc;
}

static int list_inputs(struct state *s, struct stray_error *err)
{
	struct stat st;
	size_t i;
	int rc = STRAY_OK;

	for (i = 0; rc == STRAY_OK && i < s->o->n_inputs; i++) {
		const char *p = s->o->inputs[i];

		if (lstat(p, &st) != 0)
			rc = stray_error_at(err, STRAY_ENOTFOUND, p, 0, "file",
					    "does not exist");
		else if (S_ISDIR(st.st_mode))
			rc = add_dir(s, p, err);
		else
			rc = add_input(s, NULL, p, err);
	}
	for (i = 0; i < s->n_in; i++) {
		const char *slash = strrchr(s->in[i].path, '/');

		s->in[i].base = slash ? slash + 1 : s->in[i].path;
	}
	if (rc == STRAY_OK && s->n_in == 0)
		rc = stray_error_at(err, STRAY_EINVAL, s->o->inputs[0], 0,
				    "file", "no frame files (.fits, .fit, .fts, "
				    ".tif, .tiff) among the inputs");
	return rc;
}

static int by_base(const void *a, const void *b)
{
	const struct input *const *x = a, *const *y = b;

	return strcmp((*x)->base, (*y)->base);
}

static int by_sha(const void *a, const void *b)
{
	const struct input *const *x = a, *const *y = b;

	return strcmp((*x)->sha, (*y)->sha);
}

/* Two inputs alike (by name, or by bytes): refused, both named. */
static int no_twins(struct state *s, int (*cmp)(const void *, const void *),
		    const char *field, const char *reason,
		    struct stray_error *err)
{
	static char why[PATH_LEN + 96];
	const struct input **p = malloc(s->n_in * sizeof(*p));
	size_t i;
	int rc = STRAY_OK;

	if (!p)
		return stray_error_at(err, STRAY_ENOMEM, "inputs", 0, 0, 0);
	for (i = 0; i < s->n_in; i++)
		p[i] = &s->in[i];
	qsort(p, s->n_in, sizeof(*p), cmp);
	for (i = 1; rc == STRAY_OK && i < s->n_in; i++)
		/* by bytes: only the files read (those in the log) */
		if (cmp(&p[i], &p[i - 1]) == 0 &&
		    (cmp == by_base || (p[i]->sha[0] && p[i - 1]->sha[0]))) {
			snprintf(why, sizeof(why), "%s %s", reason,
				 p[i - 1]->path);
			rc = stray_error_at(err, STRAY_EINVAL, p[i]->path, 0,
					    field, why);
			stray_error_text(err, p[i]->base);
		}
	free(p);
	return rc;
}

static int by_file(const void *key, const void *b)
{
	return strcmp((const char *)key,
		      (*(const struct stray_import_row *const *)b)->file);
}

static int by_row_file(const void *a, const void *b)
{
	return strcmp((*(const struct stray_import_row *const *)a)->file,
		      (*(const struct stray_import_row *const *)b)->file);
}

/* Each file to its log row by name; the unmatched on either side are
 * mismatches. */
static int match(struct state *s, struct stray_error *err)
{
	const struct stray_import_row **r = malloc(s->log.n * sizeof(*r));
	size_t i;

	if (!r)
		return stray_error_at(err, STRAY_ENOMEM, "log", 0, 0, 0);
	for (i = 0; i < s->log.n; i++)
		r[i] = &s->log.r[i];
	qsort(r, s->log.n, sizeof(*r), by_row_file);
	for (i = 0; i < s->n_in; i++) {
		const struct stray_import_row *const *hit = bsearch(
			s->in[i].base, r, s->log.n, sizeof(*r), by_file);

		s->in[i].row = hit ? *hit : NULL;
		if (hit)
			s->of_row[*hit - s->log.r] = &s->in[i];
	}
	free(r);
	for (i = 0; i < s->log.n; i++)
		if (!s->of_row[i])
			stray_import_missing(&s->chk, &s->log.r[i]);
	for (i = 0; i < s->n_in; i++)
		if (!s->in[i].row)
			stray_import_unlogged(&s->chk, s->in[i].path);
	return STRAY_OK;
}

/* The origin and saturation the options give, where the header does
 * not; both given must agree. */
static int settle(const struct state *s, struct stray_import_header *h,
		  const char *path, struct stray_error *err)
{
	const struct stray_import_opts *o = s->o;

	if (o->has_origin && h->has_origin &&
	    (o->col0 != h->col0 || o->row0 != h->row0))
		return stray_error_at(err, STRAY_EINVAL, path, 0,
			"XORGSUBF,YORGSUBF", "differs from --col0/--row0");
	if (o->has_satlevel && h->has_satlevel && o->satlevel != h->satlevel)
		return stray_error_at(err, STRAY_EINVAL, path, 0, "SATURATE",
				      "differs from --satlevel");
	if (!h->has_origin && o->has_origin) {
		h->col0 = o->col0;
		h->row0 = o->row0;
	}
	if (!h->has_satlevel)
		h->satlevel = o->has_satlevel ? o->satlevel : 65535;
	/* detector rows and columns are 16-bit in the store */
	if (h->col0 + (long)h->n_cols > 65536 ||
	    h->row0 + (long)h->n_rows > 65536)
		return stray_error_at(err, STRAY_EINVAL, path, 0, "COL0,ROW0",
			"the window ends past detector pixel 65535");
	return STRAY_OK;
}

/* Read, hash and check one frame's header against its row. */
static int check_frame(struct state *s, size_t i, struct stray_error *err)
{
	struct input *in = s->of_row[i];
	struct stray_import_header h;
	uint16_t *px = NULL;
	int rc;

	if ((rc = stray_sweep_file_load(in->path, &s->buf, err)))
		return rc;
	stray_sweep_sha256_mem(s->buf.data, s->buf.len, in->sha);
	/* the pixels decoded too: a truncated or corrupt frame is refused
	 * here, before anything is written */
	rc = stray_import_frame_read(in->path, &s->buf, &h, &px, err);
	free(px);
	if (rc || (rc = settle(s, &h, in->path, err)))
		return rc;
	if (!s->first_path) {
		s->first = h;
		s->first_path = in->path;
	} else if ((rc = stray_import_check_same(&s->first, s->first_path,
						   &h, in->path, err))) {
		return rc;
	}
	stray_import_check_row(&s->chk, &s->log.r[i], &h, in->base, &s->rb[i]);
	return STRAY_OK;
}

static long angle_key(double a)
{
	return lround(a * 1000.0);	/* the file name's 3 decimals */
}

static const struct stray_import_row *rows_base;

static int by_group(const void *a, const void *b)
{
	const struct stray_import_row *x = &rows_base[*(const size_t *)a];
	const struct stray_import_row *y = &rows_base[*(const size_t *)b];
	long kx = angle_key(x->angle_deg), ky = angle_key(y->angle_deg);

	if (kx != ky)
		return kx < ky ? -1 : 1;
	if (x->type != y->type)
		return x->type < y->type ? -1 : 1;
	return (x->line > y->line) - (x->line < y->line);
}

/* SEQNUM: the index of each row within its (angle, type) group in the
 * log's order, so every frame file name is new. */
static int number_rows(struct state *s, struct stray_error *err)
{
	size_t *k = malloc(s->log.n * sizeof(*k)), i;

	if (!k)
		return stray_error_at(err, STRAY_ENOMEM, s->o->log_path, 0, 0,
				      0);
	for (i = 0; i < s->log.n; i++)
		k[i] = i;
	rows_base = s->log.r;
	qsort(k, s->log.n, sizeof(*k), by_group);
	for (i = 0; i < s->log.n; i++)
		s->seq[k[i]] = i > 0 &&
			angle_key(s->log.r[k[i]].angle_deg) ==
			angle_key(s->log.r[k[i - 1]].angle_deg) &&
			s->log.r[k[i]].type == s->log.r[k[i - 1]].type
			? s->seq[k[i - 1]] + 1 : 0;
	free(k);
	return STRAY_OK;
}

static int check_all(struct state *s, struct stray_error *err)
{
	size_t i;
	int rc;

	if ((rc = no_twins(s, by_base, "file", "is a second file of that "
			   "name; the first is", err)) ||
	    (rc = match(s, err)))
		return rc;
	for (i = 0; i < s->log.n; i++)
		if (s->of_row[i] && (rc = check_frame(s, i, err)))
			return rc;
	if ((rc = no_twins(s, by_sha, "file", "has the same bytes as (one "
			   "frame given twice?)", err)))
		return rc;
	if (s->chk.n_mismatch > 0) {
		stray_error_at(err, STRAY_EINVAL, s->o->log_path, 0,
			       "mismatches", "between the log and the frames "
			       "(each reported): nothing imported");
		if (err) {
			err->value = (stray_real)s->chk.n_mismatch;
			err->has_value = 1;
		}
		return STRAY_EINVAL;
	}
	return number_rows(s, err);
}

static void state_free(struct state *s)
{
	stray_import_log_free(&s->log);
	free(s->in);
	free(s->of_row);
	free(s->rb);
	free(s->seq);
	stray_sweep_buf_free(&s->buf);
}

int stray_sweep_import(const struct stray_import_opts *o,
		       struct stray_import_result *res,
		       struct stray_error *err)
{
	struct state s;
	char *text = NULL;
	size_t len = 0;
	int rc;

	memset(&s, 0, sizeof(s));
	memset(res, 0, sizeof(*res));
	s.o = o;
	s.chk.log_name = o->log_path;
	s.chk.rotator_zero_deg = o->rotator_zero_deg;
	s.chk.mismatch = o->mismatch;
	s.chk.ctx = o->ctx;
	if ((rc = stray_file_read(o->log_path, &text, &len, err)))
		return rc;
	rc = stray_import_log_parse(o->log_path, text, len, &s.log, err);
	free(text);
	if (rc == STRAY_OK)
		rc = list_inputs(&s, err);
	if (rc == STRAY_OK) {
		s.of_row = calloc(s.log.n, sizeof(*s.of_row));
		s.rb = malloc(s.log.n * sizeof(*s.rb));
		s.seq = malloc(s.log.n * sizeof(*s.seq));
		if (!s.of_row || !s.rb || !s.seq)
			rc = stray_error_at(err, STRAY_ENOMEM, o->log_path, 0,
					    0, 0);
	}
	if (rc == STRAY_OK)
		rc = check_all(&s, err);
	res->n_mismatch = s.chk.n_mismatch;
	if (rc == STRAY_OK)
		rc = stray_import_write(o, &s.log, s.of_row, s.rb, s.seq,
					&s.first, res, err);
	state_free(&s);
	return rc;
}
