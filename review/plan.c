/*
 * plan.c - the steps of a review, each a `stray` command line (the one a
 * user would type to check it by hand), from what the project file
 * gives: a step whose inputs are absent is kept in the plan as "not run"
 * with why, so the report lists it and never fills it with other content.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "review/review.h"
#include "stray/errfmt.h"
#include "stray/sensor_io.h"

static char *dupf(const char *fmt, ...)
{
	va_list ap;
	char *s;
	int n;

	va_start(ap, fmt);
	n = vsnprintf(NULL, 0, fmt, ap);
	va_end(ap);
	if (n < 0 || !(s = malloc((size_t)n + 1)))
		return NULL;
	va_start(ap, fmt);
	vsnprintf(s, (size_t)n + 1, fmt, ap);
	va_end(ap);
	return s;
}

static void arg(struct review_step *s, char *a)
{
	if (s->argc < REVIEW_ARGV_MAX - 1)
		s->argv[s->argc++] = a;
	s->argv[s->argc] = NULL;
}

static void out(struct review_step *s, const char *name)
{
	if (s->n_outs < REVIEW_OUTS_MAX)
		s->outs[s->n_outs++] = dupf("%s", name);
}

static void in(struct review_step *s, const char *path)
{
	/* built-in names are not files: the command line carries them */
	if (strchr(path, '/') && s->n_ins < REVIEW_INS_MAX)
		s->ins[s->n_ins++] = dupf("%s", path);
}

static struct review_step *add(struct review_plan *plan, const char *name,
			       const char *title, const char *cmd,
			       double weight)
{
	struct review_step *s = &plan->step[plan->n++];

	memset(s, 0, sizeof(*s));
	s->name = name;
	s->title = title;
	s->weight = weight;
	arg(s, dupf("stray"));
	if (cmd)
		arg(s, dupf("%s", cmd));
	return s;
}

static const struct review_req *req(const struct review_project *p,
				    const char *key)
{
	int i;

	for (i = 0; i < p->n_req; i++)
		if (strcmp(p->req[i].key, key) == 0)
			return &p->req[i];
	return NULL;
}

/* --sensor S and --rate R (the tolerated false stars of the project). */
/* The project's detector (issue 28), when it names one. */
static void detector(struct review_step *s, const struct review_project *p)
{
	if (p->detector[0]) {
		arg(s, dupf("--detector"));
		arg(s, dupf("%s", p->detector));
	}
	if (p->detector_sigma > 0.0) {
		arg(s, dupf("--detector-sigma"));
		arg(s, dupf("%.17g", p->detector_sigma));
	}
}

static void sensor_rate(struct review_step *s, const struct review_project *p)
{
	const struct review_req *r = req(p, "false_stars_per_image");

	arg(s, dupf("--sensor"));
	arg(s, dupf("%s", p->sensor));
	in(s, p->sensor);
	if (r) {
		arg(s, dupf("--rate"));
		arg(s, dupf("%.17g", r->value));
	}
	detector(s, p);
}

static void scene(struct review_step *s, const struct review_project *p)
{
	int i;

	arg(s, dupf("--scene"));
	arg(s, dupf("%s", p->scene));
	in(s, p->scene);
	for (i = 0; i < p->n_set; i++) {
		arg(s, dupf("--set"));
		arg(s, dupf("%s", p->set[i]));
	}
}

static void lens_steps(struct review_plan *plan, const struct review_project *p,
		       char *lens, size_t size)
{
	struct review_step *s = add(plan, "reduce", "Lens: the lab sweep reduced",
				    "reduce", 2);

	lens[0] = '\0';
	if (p->lens == REVIEW_LENS_SWEEP) {
		arg(s, dupf("%s", p->lens_path));
		arg(s, dupf("--out"));
		arg(s, dupf("lens.csv"));
		arg(s, dupf("--json"));
		snprintf(s->stdout_file, sizeof(s->stdout_file), "reduce.json");
		in(s, p->lens_path);	/* the folder: its manifest is hashed */
		out(s, "lens.csv");
		out(s, "reduce.json");
		snprintf(lens, size, "lens.csv");
	} else {
		s->why = p->lens == REVIEW_LENS_NONE ?
			"the project names no lens: the baffle alone is traced" :
			p->lens == REVIEW_LENS_IDEAL ?
			"the lens is the ideal lens, not a lab sweep" :
			"the lens is given as a curve, not as a lab sweep";
		if (p->lens == REVIEW_LENS_CSV)
			snprintf(lens, size, "%s", p->lens_path);
		else if (p->lens == REVIEW_LENS_IDEAL)
			snprintf(lens, size, "ideal:%.17g", p->lens_fov_deg);
	}
}

static double mission_altitude(const struct review_project *p)
{
	return p->mission == REVIEW_MISSION_ORBIT ? p->altitude_km : 550.0;
}

static void mission_steps(struct review_plan *plan,
			  const struct review_project *p)
{
	struct review_step *s = add(plan, "mission", "Mission: orbit and attitude",
				    "availability", 1);
	const char *oem = "mission.oem", *aem = "mission.aem";
	int i;

	if (p->mission == REVIEW_MISSION_ORBIT) {
		arg(s, dupf("--write-oem")); arg(s, dupf("mission.oem"));
		arg(s, dupf("--write-aem")); arg(s, dupf("mission.aem"));
		arg(s, dupf("--altitude-km")); arg(s, dupf("%.17g", p->altitude_km));
		if (p->ltan[0]) {
			arg(s, dupf("--ltan")); arg(s, dupf("%s", p->ltan));
		} else {
			arg(s, dupf("--inclination-deg"));
			arg(s, dupf("%.17g", p->incl_deg));
		}
		arg(s, dupf("--epoch")); arg(s, dupf("%s", p->epoch));
		arg(s, dupf("--hours")); arg(s, dupf("%.17g", p->hours));
		arg(s, dupf("--gen-step-s")); arg(s, dupf("%.17g", p->step_s));
		arg(s, dupf("--attitude")); arg(s, dupf("%s", p->attitude));
		out(s, "mission.oem");
		out(s, "mission.aem");
	} else {
		s->why = p->mission == REVIEW_MISSION_NONE ?
			"the project names no mission" :
			"the project gives its own OEM/AEM files";
		oem = p->oem;
		aem = p->aem;
	}
	s = add(plan, "availability", "Availability along the mission",
		"availability", 1 + (p->mission == REVIEW_MISSION_ORBIT ?
				     p->hours / 12.0 : 2.0));
	if (p->mission == REVIEW_MISSION_NONE || !p->n_heads) {
		s->why = p->mission == REVIEW_MISSION_NONE ?
			 "the project names no mission" : "the project names no heads";
		return;
	}
	arg(s, dupf("--oem")); arg(s, dupf("%s", oem));
	arg(s, dupf("--aem")); arg(s, dupf("%s", aem));
	arg(s, dupf("--heads")); arg(s, dupf("heads.json"));
	detector(s, p);		/* the flight table must be built for it */
	arg(s, dupf("--plot")); arg(s, dupf("availability"));
	arg(s, dupf("--out")); arg(s, dupf("availability.csv"));
	arg(s, dupf("--json"));
	snprintf(s->stdout_file, sizeof(s->stdout_file), "availability.json");
	in(s, oem[0] == '/' ? oem : "./mission.oem");
	in(s, aem[0] == '/' ? aem : "./mission.aem");
	in(s, "./heads.json");
	in(s, "./flight_table.bin");
	out(s, "availability.json");
	out(s, "availability.csv");
	out(s, "availability_timeline.png");
	out(s, "availability_fdr.png");
	for (i = 0; i < p->n_heads; i++) {
		char name[64];

		snprintf(name, sizeof(name), "availability_sky_%s.png",
			 p->head[i].name);
		out(s, name);
	}
}

int review_plan_make(const struct review_project *p, long rays,
		     struct review_plan *plan, struct stray_error *err)
{
	struct review_project q = *p;
	struct stray_sensor sensor;
	struct review_step *s;
	char lens[REVIEW_PATH_MAX];
	int rc, i;

	memset(plan, 0, sizeof(*plan));
	plan->rays = rays;
	/* the ideal lens's field is the sensor's unless the project says */
	if (q.lens == REVIEW_LENS_IDEAL && q.lens_fov_deg == 0.0) {
		if ((rc = stray_sensor_load(q.sensor, &sensor, err)) != STRAY_OK)
			return rc;
		q.lens_fov_deg = sensor.fov_half_deg;
	}
	p = &q;
	s = add(plan, "photometry", "Photometry of the sensor", "photometry", 0.2);
	arg(s, dupf("--sensor")); arg(s, dupf("%s", p->sensor));
	in(s, p->sensor);
	arg(s, dupf("--json"));
	snprintf(s->stdout_file, sizeof(s->stdout_file), "photometry.json");
	out(s, "photometry.json");

	s = add(plan, "fdr", "False detections and the attenuation required", "fdr", 0.2);
	sensor_rate(s, p);
	arg(s, dupf("--plot")); arg(s, dupf("fdr.png"));
	arg(s, dupf("--json"));
	snprintf(s->stdout_file, sizeof(s->stdout_file), "fdr.json");
	out(s, "fdr.json");
	out(s, "fdr.png");

	lens_steps(plan, p, lens, sizeof(lens));

	s = add(plan, "trace", "System curve: the baffle traced with the lens",
		"trace", 1.0 + (double)rays / 2e5);
	scene(s, p);
	if (lens[0]) {
		arg(s, dupf("--lens")); arg(s, dupf("%s", lens));
		in(s, strcmp(lens, "lens.csv") == 0 ? "./lens.csv" : lens);
	}
	arg(s, dupf("--rays")); arg(s, dupf("%ld", rays));
	/* 1-deg rows: <= 128, as the flight table takes them */
	arg(s, dupf("--angles")); arg(s, dupf("0:90:1"));
	arg(s, dupf("--out")); arg(s, dupf("system.csv"));
	arg(s, dupf("--plot")); arg(s, dupf("system.png"));
	arg(s, dupf("--plot-orders")); arg(s, dupf("orders.png"));
	arg(s, dupf("--export-obj")); arg(s, dupf("scene.obj"));
	arg(s, dupf("--json"));
	snprintf(s->stdout_file, sizeof(s->stdout_file), "trace.json");
	out(s, "system.csv"); out(s, "system.png"); out(s, "orders.png");
	out(s, "scene.obj"); out(s, "trace.json");

	s = add(plan, "exclusion", "Exclusion angles of the Sun, Moon and Earth",
		"exclusion", 0.2);
	arg(s, dupf("--curve")); arg(s, dupf("system.csv"));
	in(s, "./system.csv");
	sensor_rate(s, p);
	arg(s, dupf("--earth-albedo")); arg(s, dupf("0.3"));
	arg(s, dupf("--altitude-km")); arg(s, dupf("%.17g", mission_altitude(p)));
	arg(s, dupf("--plot")); arg(s, dupf("exclusion.png"));
	arg(s, dupf("--json"));
	snprintf(s->stdout_file, sizeof(s->stdout_file), "exclusion.json");
	out(s, "exclusion.json"); out(s, "exclusion.png");

	/* the false stars a frame sees at the required Sun angle: the
	 * alpha is read from system.csv when the step runs (@ALPHA) */
	s = add(plan, "fdr_at_requirement",
		"False stars at the required Sun exclusion angle", "fdr", 0.2);
	if (!req(p, "sun_exclusion_deg_max")) {
		s->why = "the project has no sun_exclusion_deg_max";
	} else {
		sensor_rate(s, p);
		arg(s, dupf("--alpha")); arg(s, dupf("@ALPHA"));
		arg(s, dupf("--json"));
		in(s, "./system.csv");
		snprintf(s->stdout_file, sizeof(s->stdout_file), "fdr_at_requirement.json");
		out(s, "fdr_at_requirement.json");
	}

	s = add(plan, "diagnose", "Diagnosis of the measured curve", "diagnose",
		1.0 + 4.0 * (double)rays / 2e5);
	if (!p->measured[0]) {
		s->why = "the project names no measured curve";
	} else {
		arg(s, dupf("%s", p->measured));	/* the operand first */
		in(s, p->measured);
		scene(s, p);
		if (p->measured_system && lens[0]) {
			arg(s, dupf("--lens")); arg(s, dupf("%s", lens));
			in(s, strcmp(lens, "lens.csv") == 0 ? "./lens.csv" : lens);
		}
		arg(s, dupf("--sensor")); arg(s, dupf("%s", p->sensor));
		arg(s, dupf("--rays")); arg(s, dupf("%ld", rays / 5 > 1000 ? rays / 5 : 1000));
		arg(s, dupf("--threads")); arg(s, dupf("2"));
		arg(s, dupf("--plot")); arg(s, dupf("diagnose.png"));
		arg(s, dupf("--json"));
		snprintf(s->stdout_file, sizeof(s->stdout_file), "diagnose.json");
		out(s, "diagnose.json"); out(s, "diagnose.png");
	}

	s = add(plan, "firmware_table", "Flight table", "firmware-table", 0.2);
	arg(s, dupf("--curve")); arg(s, dupf("system.csv"));
	in(s, "./system.csv");
	sensor_rate(s, p);
	arg(s, dupf("--earth-albedo")); arg(s, dupf("0.3"));
	arg(s, dupf("--out-bin")); arg(s, dupf("flight_table.bin"));
	arg(s, dupf("--out-c")); arg(s, dupf("flight_table.c"));
	arg(s, dupf("--json"));
	snprintf(s->stdout_file, sizeof(s->stdout_file), "firmware.json");
	out(s, "firmware.json"); out(s, "flight_table.bin"); out(s, "flight_table.c");

	mission_steps(plan, p);
	for (i = 0; i < plan->n; i++)
		if (!plan->step[i].argv[plan->step[i].argc - 1])
			return stray_error_set(err, STRAY_ENOMEM, "plan", NULL);
	return STRAY_OK;
}

void review_plan_free(struct review_plan *plan)
{
	int i, k;

	for (i = 0; i < plan->n; i++) {
		struct review_step *s = &plan->step[i];

		for (k = 0; k < s->argc; k++)
			free(s->argv[k]);
		for (k = 0; k < s->n_ins; k++)
			free(s->ins[k]);
		for (k = 0; k < s->n_outs; k++)
			free(s->outs[k]);
	}
	plan->n = 0;
}
