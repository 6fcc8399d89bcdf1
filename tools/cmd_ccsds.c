/*
 * cmd_ccsds.c - `stray ccsds check FILE`: an OEM or AEM as the toolkit
 * reads it (segments, frames, time system, span, first and last state),
 * so a user sees their file as `stray availability` and `stray
 * flightcheck` will fly it, before flying it.  A thin command over
 * libstray's readers.
 */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "stray/aem.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/oem.h"

static const char usage[] =
	"usage: stray ccsds check FILE [--iers finals2000A.all] [--json]\n"
	"\n"
	"Read a CCSDS OEM (502.0) or AEM (504.0) in KVN text as `stray\n"
	"availability` and `stray flightcheck` read it, and print what was\n"
	"read: version, object, time system, each segment (its frame, its\n"
	"attitude type, its records, its useable span, its covariance\n"
	"matrices), the span covered, the holes interpolation will not\n"
	"cross, and the first and last state in the inertial frame (position\n"
	"and velocity, or the quaternion q_ib = (q_c, e) with v_body =\n"
	"M(q) v_inertial).  A file the readers refuse is named with its line.\n"
	"\n"
	"  --iers F     UT1 - UTC and the pole from an IERS finals table for\n"
	"               Earth-fixed frames (zero without one)\n"
	"  --json       the same, machine-readable\n";

static const char *const ts_names[] = { "UTC", "TAI", "TT", "GPS" };

static void epoch(double t, int ts, char *buf, size_t n)
{
	stray_ccsds_format_epoch(t, ts, buf, n);
}

static cJSON *vec(const double *x, int n)
{
	cJSON *a = cJSON_CreateArray();
	int i;

	for (i = 0; i < n; i++)
		cJSON_AddItemToArray(a, cli_json_number(x[i]));
	return a;
}

/* What both messages share: header, span, segments. */
static cJSON *common(const char *path, const char *kind, double version,
		     const char *object, int ts,
		     const struct stray_ccsds_cover *c, size_t n,
		     const double *t)
{
	cJSON *o = cJSON_CreateObject(), *segs = cJSON_CreateArray();
	char e0[40], e1[40];
	size_t i;

	epoch(c->t0, ts, e0, sizeof(e0));
	epoch(c->t1, ts, e1, sizeof(e1));
	cJSON_AddStringToObject(o, "file", path);
	cJSON_AddStringToObject(o, "message", kind);
	cJSON_AddNumberToObject(o, "version", version);
	cJSON_AddStringToObject(o, "object_name", object);
	cJSON_AddStringToObject(o, "time_system", ts_names[ts]);
	cJSON_AddStringToObject(o, "start", e0);
	cJSON_AddStringToObject(o, "stop", e1);
	cJSON_AddNumberToObject(o, "span_s", c->t1 - c->t0);
	cJSON_AddNumberToObject(o, "records", (double)n);
	cJSON_AddNumberToObject(o, "holes", (double)stray_ccsds_cover_holes(c, t));
	for (i = 0; i < c->n_seg; i++) {
		const struct stray_ccsds_seg *s = &c->seg[i];
		cJSON *j = cJSON_CreateObject();
		size_t k, owned = 0;

		for (k = 0; k < c->n_piece; k++)
			owned += c->piece[k].seg == i;
		epoch(s->u0, ts, e0, sizeof(e0));
		epoch(s->u1, ts, e1, sizeof(e1));
		cJSON_AddNumberToObject(j, "line", (double)s->line);
		cJSON_AddStringToObject(j, "frame", s->frame_name);
		cJSON_AddBoolToObject(j, "converted_to_inertial",
				      s->frame != STRAY_FRAME_INERTIAL);
		if (s->kind[0])
			cJSON_AddStringToObject(j, "attitude_type", s->kind);
		cJSON_AddNumberToObject(j, "records", (double)s->n);
		cJSON_AddStringToObject(j, "useable_start", e0);
		cJSON_AddStringToObject(j, "useable_stop", e1);
		cJSON_AddNumberToObject(j, "owned_stretches", (double)owned);
		if (strcmp(kind, "OEM") == 0)
			cJSON_AddNumberToObject(j, "covariance_matrices", (double)s->n_cov);
		cJSON_AddItemToArray(segs, j);
	}
	cJSON_AddItemToObject(o, "segments", segs);
	return o;
}

static void add_state(cJSON *o, const char *name, double t, int ts,
		      const double *a, int na, const double *b)
{
	cJSON *j = cJSON_CreateObject();
	char e[40];

	epoch(t, ts, e, sizeof(e));
	cJSON_AddStringToObject(j, "epoch", e);
	if (b) {
		cJSON_AddItemToObject(j, "r_km", vec(a, 3));
		cJSON_AddItemToObject(j, "v_km_s", vec(b, 3));
	} else {
		cJSON_AddItemToObject(j, "q_ib", vec(a, na));
	}
	cJSON_AddItemToObject(o, name, j);
}

static int check_oem(const char *path, const char *buf, size_t len,
		     struct stray_error *err, cJSON **out)
{
	struct stray_oem o;
	double r[3], v[3];
	int rc = stray_oem_parse(buf, len, path, &o, err);

	if (rc != STRAY_OK)
		return rc;
	*out = common(path, "OEM", o.version, o.object_name, o.time_system,
		      &o.cover, o.n, o.t);
	/* a useable span may open inside a gap: then there is no state */
	if (stray_oem_state(&o, o.cover.t0, r, v) == STRAY_OK)
		add_state(*out, "first", o.cover.t0, o.time_system, r, 3, v);
	if (stray_oem_state(&o, o.cover.t1, r, v) == STRAY_OK)
		add_state(*out, "last", o.cover.t1, o.time_system, r, 3, v);
	stray_oem_free(&o);
	return STRAY_OK;
}

static int check_aem(const char *path, const char *buf, size_t len,
		     struct stray_error *err, cJSON **out)
{
	struct stray_aem a;
	double q[4];
	int rc = stray_aem_parse(buf, len, path, &a, err);

	if (rc != STRAY_OK)
		return rc;
	*out = common(path, "AEM", a.version, a.object_name, a.time_system,
		      &a.cover, a.n, a.t);
	if (stray_aem_attitude(&a, a.cover.t0, q) == STRAY_OK)
		add_state(*out, "first", a.cover.t0, a.time_system, q, 4, NULL);
	if (stray_aem_attitude(&a, a.cover.t1, q) == STRAY_OK)
		add_state(*out, "last", a.cover.t1, a.time_system, q, 4, NULL);
	stray_aem_free(&a);
	return STRAY_OK;
}

static double num(const cJSON *o, const char *k)
{
	return cJSON_GetObjectItem(o, k)->valuedouble;
}

static const char *str(const cJSON *o, const char *k)
{
	return cJSON_GetObjectItem(o, k)->valuestring;
}

static void print_state(const cJSON *o, const char *name)
{
	const cJSON *s = cJSON_GetObjectItem(o, name), *x;
	const cJSON *r = cJSON_GetObjectItem(s, "r_km");

	if (!s) {
		printf("  %-5s none: the span's end lies in a gap\n", name);
		return;
	}
	printf("  %-5s %s  ", name, str(s, "epoch"));
	if (r) {
		const cJSON *v = cJSON_GetObjectItem(s, "v_km_s");

		printf("r = (");
		cJSON_ArrayForEach(x, r)
			printf("%s%.3f", x == r->child ? "" : ", ", x->valuedouble);
		printf(") km  v = (");
		cJSON_ArrayForEach(x, v)
			printf("%s%.6f", x == v->child ? "" : ", ", x->valuedouble);
		printf(") km/s\n");
		return;
	}
	r = cJSON_GetObjectItem(s, "q_ib");
	printf("q_ib = (");
	cJSON_ArrayForEach(x, r)
		printf("%s%.9f", x == r->child ? "" : ", ", x->valuedouble);
	printf(")\n");
}

static void print_text(const cJSON *o)
{
	const cJSON *s;
	int k = 0;

	printf("%s: CCSDS %s %.1f, object '%s', time system %s\n",
	       str(o, "file"), str(o, "message"), num(o, "version"),
	       str(o, "object_name"), str(o, "time_system"));
	printf("  covered %s .. %s (%.3f s), %.0f records, %.0f hole(s) not interpolated across\n",
	       str(o, "start"), str(o, "stop"), num(o, "span_s"),
	       num(o, "records"), num(o, "holes"));
	cJSON_ArrayForEach(s, cJSON_GetObjectItem(o, "segments")) {
		const cJSON *at = cJSON_GetObjectItem(s, "attitude_type");
		const cJSON *cv = cJSON_GetObjectItem(s, "covariance_matrices");

		printf("  segment %d (META_START line %.0f): %s%s%s%s, %.0f records, useable %s .. %s, owns %.0f stretch(es)",
		       ++k, num(s, "line"), str(s, "frame"),
		       cJSON_IsTrue(cJSON_GetObjectItem(s, "converted_to_inertial")) ?
		       " (converted to inertial)" : "", at ? ", " : "",
		       at ? at->valuestring : "", num(s, "records"),
		       str(s, "useable_start"), str(s, "useable_stop"),
		       num(s, "owned_stretches"));
		if (cv)
			printf(", %.0f covariance matrices", cv->valuedouble);
		printf("\n");
	}
	print_state(o, "first");
	print_state(o, "last");
}

int cmd_ccsds(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "iers", required_argument, NULL, 'i' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	const char *cmd = "ccsds", *iers = NULL, *a, *o;
	struct stray_error err;
	cJSON *out = NULL;
	char *buf;
	size_t len;
	int opt, rc;

	while ((opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 0: break;
		case 'h': fputs(usage, stdout); return CLI_OK;
		case 'i': iers = optarg; break;
		default:
			return cli_usage_error(cmd, "unknown option '%s'", argv[optind - 1]);
		}
	}
	if (argc - optind != 2 || strcmp(argv[optind], "check") != 0)
		return cli_usage_error(cmd, "give 'check FILE'");
	stray_error_clear(&err);
	if (iers && (rc = stray_ccsds_eop_load(iers, &err)) != STRAY_OK)
		return cli_fail(cmd, &err);
	if ((rc = stray_file_read(argv[optind + 1], &buf, &len, &err)) != STRAY_OK)
		return cli_fail(cmd, &err);
	/* the message is what its first keyword says */
	a = strstr(buf, "CCSDS_AEM_VERS");
	o = strstr(buf, "CCSDS_OEM_VERS");
	if (a && (!o || a < o))
		rc = check_aem(argv[optind + 1], buf, len, &err, &out);
	else
		rc = check_oem(argv[optind + 1], buf, len, &err, &out);
	free(buf);
	stray_ccsds_eop_clear();
	if (rc != STRAY_OK)
		return cli_fail(cmd, &err);
	if (cli.json)
		return cli_json_emit(out);
	print_text(out);
	cJSON_Delete(out);
	return CLI_OK;
}
