/*
 * review.h - `stray review`: the design review of the user's own system
 * from one project file (issue 25, docs/review.md).  The project file is
 * parsed here (unknown keys are an error, paths relative to the file),
 * turned into a plan of steps, each step one `stray` command line run by
 * exec of the stray binary, recorded in a manifest (DIR/manifest.json)
 * with the SHA-256 of its inputs, so that --resume skips what is done.
 * review.json and the report are built from that manifest only.
 */
#ifndef REVIEW_REVIEW_H
#define REVIEW_REVIEW_H

#include <stddef.h>

#include "stray/error.h"

#define REVIEW_PATH_MAX 1024
#define REVIEW_SET_MAX 24
#define REVIEW_REQ_MAX 5
#define REVIEW_HEADS_MAX 8
#define REVIEW_STEPS_MAX 12
#define REVIEW_ARGV_MAX 48
#define REVIEW_OUTS_MAX 16
#define REVIEW_INS_MAX 6

enum review_lens { REVIEW_LENS_NONE, REVIEW_LENS_IDEAL, REVIEW_LENS_CSV,
		   REVIEW_LENS_SWEEP };
enum review_mission { REVIEW_MISSION_NONE, REVIEW_MISSION_FILES,
		      REVIEW_MISSION_ORBIT };

/* The requirements known to the review, in the order of review.md. */
struct review_req {
	const char *key;	/* static: one of review_req_keys */
	double value;
};

struct review_head {
	char name[32];
	double boresight[3], up[3];
};

struct review_project {
	char path[REVIEW_PATH_MAX];	/* the project file, absolute */
	char dir[REVIEW_PATH_MAX];	/* its folder: paths are relative to it */
	char name[128];
	char sensor[REVIEW_PATH_MAX];	/* absolute path or built-in name */
	char scene[REVIEW_PATH_MAX];
	char set[REVIEW_SET_MAX][96];	/* "key=value", as --set takes it */
	int n_set;
	enum review_lens lens;
	char lens_path[REVIEW_PATH_MAX];	/* CSV or sweep folder */
	double lens_fov_deg;		/* ideal: the field half-angle */
	struct review_req req[REVIEW_REQ_MAX];
	int n_req;
	char measured[REVIEW_PATH_MAX];	/* "" = none */
	int measured_system;		/* kind "system": traced with the lens */
	enum review_mission mission;
	char oem[REVIEW_PATH_MAX], aem[REVIEW_PATH_MAX];
	double altitude_km, incl_deg;	/* incl_deg < 0: sun-synchronous */
	char ltan[8], epoch[16], attitude[16];
	double hours, step_s;
	struct review_head head[REVIEW_HEADS_MAX];
	int n_heads;
	/* "detector", "detector_sigma" (issue 28): the tracker's detector,
	 * passed to the fdr, exclusion, flight-table and availability steps;
	 * "" / 0: the sensor file's, else thesis */
	char detector[16];
	double detector_sigma;
};

/* Parse PROJECT.json; errors name the file, the key and the value. */
int review_project_load(const char *path, struct review_project *p,
			struct stray_error *err);

/* The same from text: path names the file in errors, dir resolves the
 * paths it gives (a fuzz target's entry). */
int review_project_parse(const char *path, const char *dir, const char *text,
			 size_t len, struct review_project *p,
			 struct stray_error *err);

/* One step: a stray command line run in the output folder. */
struct review_step {
	const char *name;		/* static */
	const char *title;		/* static: the report's heading */
	char *argv[REVIEW_ARGV_MAX];	/* argv[0] = "stray"; NULL-ended */
	int argc;
	char stdout_file[64];		/* "" = stdout discarded */
	char *ins[REVIEW_INS_MAX];	/* input files hashed for --resume */
	int n_ins;
	char *outs[REVIEW_OUTS_MAX];	/* outputs expected, relative to DIR */
	int n_outs;
	const char *why;		/* not run: why (static), else NULL */
	double weight;			/* relative cost, for the ETA */
	/* filled by the runner */
	const char *status;		/* "done", "not run", "failed" */
	char fail[192];			/* why it failed or was skipped */
	double seconds;
	char hash[65];
};

struct review_plan {
	struct review_step step[REVIEW_STEPS_MAX];
	int n;
	long rays;
};

/* The steps the project's inputs allow, in order; the others listed as
 * not run with why.  rays: detector-side paths of the system trace. */
int review_plan_make(const struct review_project *p, long rays,
		     struct review_plan *plan, struct stray_error *err);
void review_plan_free(struct review_plan *plan);

/*
 * Run the plan in dir with the stray binary self (exec), progress and an
 * ETA on stderr; resume: keep a step whose outputs exist and whose input
 * hash is the manifest's.  Writes dir/manifest.json after every step.
 * Returns STRAY_OK when every runnable step is done.
 */
int review_run(const char *self, const char *dir,
	       const struct review_project *p, struct review_plan *plan,
	       int resume, struct stray_error *err);

/* The largest alpha of the curve CSV at theta >= theta_deg (with the
 * sigma of that row): what a frame sees anywhere beyond the angle. */
int review_alpha_beyond(const char *csv, double theta_deg, double *alpha,
			double *sigma, struct stray_error *err);

/* dir/review.json (the verdicts and the steps), dir/design.png and the
 * report (dir/report.html, dir/report.md), from the manifest's outputs. */
int review_write(const char *dir, const struct review_project *p,
		 const struct review_plan *plan, struct stray_error *err);

/* The section drawing of the traced scene (dir/scene.obj, y = 0 cut)
 * into png; STRAY_OK or an error naming the mesh. */
int review_draw_section(const char *obj, const char *png,
			struct stray_error *err);

#endif /* REVIEW_REVIEW_H */
