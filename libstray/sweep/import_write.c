/*
 * import_write.c - the checked import written (sweep_import.h): a sweep
 * folder filled as a temporary (stray_dir_open_atomic), each frame in
 * the log's order through the store's own writer (stray_sweep_store_
 * append: our keywords, the manifest row, SHA-256), the original copied
 * byte for byte to original/, import.csv tying them; renamed into place
 * when every frame is in, removed otherwise.
 */
#define _DEFAULT_SOURCE		/* fsync */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "import_priv.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define IMPORT_CSV "import.csv"
#define ORIGINALS "original"
/* a path inside the temporary folder (struct stray_dir_out's tmp) */
#define TMP_PATH_LEN (4096 + STRAY_SWEEP_FILE_MAX + 16)

struct writer {
	const struct stray_import_opts *o;
	struct stray_dir_out dir;
	struct stray_sweep_manifest m;
	struct stray_sweep_buf buf;
	FILE *csv;
	char csv_path[TMP_PATH_LEN];
	uint16_t *det_rows;
};

static int io_fail(const char *path, const char *reason,
		   struct stray_error *err)
{
	int e = errno;

	stray_error_at(err, STRAY_EIO, path, 0, "file", reason);
	stray_error_text(err, strerror(e));
	return STRAY_EIO;
}

/* The original's bytes, as read and hashed, to original/NAME. */
static int copy_original(struct writer *w, const struct stray_import_input *in,
			 struct stray_error *err)
{
	char path[TMP_PATH_LEN];
	const unsigned char *p = w->buf.data;
	size_t left = w->buf.len;
	int fd, ok = 1;

	snprintf(path, sizeof(path), "%s/" ORIGINALS "/%s", w->dir.tmp,
		 in->base);
	fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
	if (fd < 0)
		return io_fail(path, "cannot create the copy", err);
	while (ok && left > 0) {
		ssize_t n = write(fd, p, left);

		if (n < 0 && errno == EINTR)
			continue;
		ok = n > 0;
		if (ok) {
			p += n;
			left -= (size_t)n;
		}
	}
	ok = ok && fsync(fd) == 0;
	if (close(fd) != 0 || !ok)
		return io_fail(path, "cannot write the copy; free space", err);
	return STRAY_OK;
}

/* text as a FITS string value: printable ASCII only (cfitsio refuses
 * the rest), up to 68 characters; import.csv keeps the name as it is. */
static void fits_text(char *out, size_t size, const char *text)
{
	size_t i;

	for (i = 0; i + 1 < size && text[i]; i++)
		out[i] = (unsigned char)text[i] < 0x20 ||
			 (unsigned char)text[i] > 0x7e ? '?' : text[i];
	out[i] = '\0';
}

/* Our keywords beyond the lab frame's: where the frame came from, the
 * read-back angle, and what the camera's header said of its setting. */
static size_t extras(const struct stray_import_header *h,
		     const struct stray_import_input *in,
		     const struct stray_import_row *row, double rb,
		     struct stray_sweep_key *k)
{
	static char orig[69], filter[69];
	size_t n = 0;
	int s;

	fits_text(orig, sizeof(orig), in->base);
	fits_text(filter, sizeof(filter), h->filter[0] ? h->filter
		  : row->filter);
	k[n++] = (struct stray_sweep_key){ "ORIGFILE", STRAY_SWEEP_KEY_STRING,
		0, 0, orig, "original file (original/, import.csv)" };
	k[n++] = (struct stray_sweep_key){ "ORIGSHA", STRAY_SWEEP_KEY_STRING,
		0, 0, in->sha, "SHA-256 of the original file" };
	k[n++] = (struct stray_sweep_key){ "ORIGFMT", STRAY_SWEEP_KEY_STRING,
		0, 0, h->format == STRAY_IMPORT_FITS ? "FITS" : "TIFF",
		"format of the original" };
	k[n++] = (struct stray_sweep_key){ "LOGLINE", STRAY_SWEEP_KEY_LONG,
		0, row->line, NULL, "line of the frame in the import log" };
	if (!isnan(rb))
		k[n++] = (struct stray_sweep_key){ STRAY_SWEEP_KEY_ANGLERB,
			STRAY_SWEEP_KEY_DOUBLE, rb, 0, NULL,
			"[deg] stage read-back angle" };
	if (h->filter[0] || row->filter[0])
		k[n++] = (struct stray_sweep_key){ "FILTER",
			STRAY_SWEEP_KEY_STRING, 0, 0, filter,
			"filter in the beam" };
	for (s = 0; s < STRAY_IMPORT_SETTINGS; s++)
		if (h->has_setting[s])
			k[n++] = (struct stray_sweep_key){
				stray_import_setting_key(s),
				STRAY_SWEEP_KEY_DOUBLE, h->setting[s], 0, NULL,
				"as in the original header" };
	return n;
}

static int one_frame(struct writer *w, const struct stray_import_row *row,
		     const struct stray_import_input *in, double rb, long seq,
		     const struct stray_import_header *first,
		     struct stray_error *err)
{
	struct stray_sweep_key k[16];
	struct stray_import_header h;
	struct stray_sweep_frame f;
	struct stray_sweep_image im;
	char sha[STRAY_SWEEP_SHA256_HEX];
	uint16_t *px = NULL;
	int rc;

	if ((rc = stray_sweep_file_load(in->path, &w->buf, err)))
		return rc;
	stray_sweep_sha256_mem(w->buf.data, w->buf.len, sha);
	if (strcmp(sha, in->sha) != 0)
		return stray_error_at(err, STRAY_EIO, in->path, 0, "file",
			"changed while being imported; import again");
	if ((rc = stray_import_frame_read(in->path, &w->buf, &h, &px, err)))
		return rc;
	memset(&f, 0, sizeof(f));
	f.type = row->type;
	f.angle_deg = row->angle_deg;
	/* the camera's own record of the exposure, checked against the log */
	f.exptime_s = h.has_exptime ? h.exptime_s : row->exptime_s;
	f.ndtrans = row->ndtrans;
	f.seqnum = seq;
	f.sat_dn = first->satlevel;
	f.full_frame = 1;	/* a contiguous window from ROW0: no ROWS */
	f.has_monitor = !isnan(row->monitor);
	f.monitor = row->monitor;
	f.instrument = h.instrume[0] ? h.instrume : "unknown (imported)";
	f.extra = k;
	f.n_extra = extras(&h, in, row, rb, k);
	f.date_obs = h.has_date ? h.date_obs : isnan(row->date_obs) ? 0.0
		     : row->date_obs;
	im.n_rows = h.n_rows;
	im.n_cols = h.n_cols;
	im.col0 = first->col0;
	im.rows = w->det_rows;
	im.px = px;
	rc = stray_sweep_store_append(&w->m, &f, &im, err);
	free(px);
	if (rc == STRAY_OK)
		rc = copy_original(w, in, err);
	if (rc == STRAY_OK &&
	    fprintf(w->csv, "%s,%s,%s,%ld,%s\n", w->m.e[w->m.n - 1].file,
		    in->base, in->sha, row->line,
		    h.format == STRAY_IMPORT_FITS ? "FITS" : "TIFF") < 0)
		rc = io_fail(w->csv_path, "cannot write", err);
	return rc;
}

static int open_all(struct writer *w, const struct stray_import_header *first,
		    struct stray_error *err)
{
	char path[TMP_PATH_LEN];
	size_t r;
	int rc;

	if (!(w->det_rows = malloc(first->n_rows * sizeof(*w->det_rows))))
		return stray_error_at(err, STRAY_ENOMEM, w->o->out_dir, 0, 0,
				      0);
	for (r = 0; r < first->n_rows; r++)
		w->det_rows[r] = (uint16_t)(first->row0 + (long)r);
	if ((rc = stray_dir_open_atomic(&w->dir, w->o->out_dir, err)))
		return rc;
	if ((rc = stray_sweep_store_open(&w->m, w->dir.tmp, 0, err)))
		return rc;
	snprintf(path, sizeof(path), "%s/" ORIGINALS, w->dir.tmp);
	if (mkdir(path, 0755) != 0)
		return io_fail(path, "cannot create the folder", err);
	snprintf(w->csv_path, sizeof(w->csv_path), "%s/" IMPORT_CSV,
		 w->dir.tmp);
	if (!(w->csv = fopen(w->csv_path, "wx")))
		return io_fail(w->csv_path, "cannot create", err);
	if (fprintf(w->csv, "# stray sweep import: each frame of this folder "
		    "and the file it was made from (original/)\n"
		    "frame,original,original_sha256,log_line,format\n") < 0)
		return io_fail(w->csv_path, "cannot write", err);
	return STRAY_OK;
}

static int close_csv(struct writer *w, struct stray_error *err)
{
	int ok = fflush(w->csv) == 0 && fsync(fileno(w->csv)) == 0;

	ok = fclose(w->csv) == 0 && ok;
	w->csv = NULL;
	return ok ? STRAY_OK : io_fail(w->csv_path, "cannot write", err);
}

static void count(const struct stray_import_log *log,
		  const struct stray_import_header *first,
		  struct stray_import_result *res)
{
	size_t i;

	res->n_frames = log->n;
	res->n_rows = first->n_rows;
	res->n_cols = first->n_cols;
	res->col0 = first->col0;
	res->row0 = first->row0;
	res->satlevel = first->satlevel;
	snprintf(res->instrume, sizeof(res->instrume), "%s", first->instrume);
	for (i = 0; i < log->n; i++) {
		const struct stray_import_row *r = &log->r[i];

		res->n_dark += r->type == STRAY_SWEEP_DARK;
		res->n_ambient += r->type == STRAY_SWEEP_AMBIENT;
		res->n_full += r->type == STRAY_SWEEP_FULL;
		/* a new angle where the previous row had another */
		res->n_angles += i == 0 || fabs(r->angle_deg -
						log->r[i - 1].angle_deg) > 1e-6;
	}
}

int stray_import_write(const struct stray_import_opts *o,
		       const struct stray_import_log *log,
		       struct stray_import_input *const *of_row,
		       const double *rb, const long *seq,
		       const struct stray_import_header *first,
		       struct stray_import_result *res,
		       struct stray_error *err)
{
	struct writer w;
	size_t i;
	int rc, dir_open;

	memset(&w, 0, sizeof(w));
	w.o = o;
	w.m.lock_fd = -1;
	rc = open_all(&w, first, err);
	dir_open = w.dir.tmp[0] != '\0';
	for (i = 0; rc == STRAY_OK && i < log->n; i++)
		rc = one_frame(&w, &log->r[i], of_row[i], rb[i], seq[i], first,
			       err);
	for (i = 0, res->dated = rc == STRAY_OK; rc == STRAY_OK && i < w.m.n;
	     i++) {
		res->readback |= !isnan(rb[i]);
		res->dated &= !isnan(w.m.e[i].date_obs);
	}
	if (w.csv && rc == STRAY_OK)
		rc = close_csv(&w, err);
	else if (w.csv)
		fclose(w.csv);
	stray_sweep_manifest_free(&w.m);	/* the lock */
	free(w.det_rows);
	stray_sweep_buf_free(&w.buf);
	if (rc == STRAY_OK)
		rc = stray_dir_commit(&w.dir, err);
	else if (dir_open)
		stray_dir_abort(&w.dir);
	if (rc == STRAY_OK) {
		count(log, first, res);
		/* one format per sweep (stray_import_check_same) */
		if (first->format == STRAY_IMPORT_FITS)
			res->n_fits = res->n_frames;
		else
			res->n_tiff = res->n_frames;
	}
	return rc;
}
