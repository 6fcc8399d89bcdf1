/*
 * scene.h - what the tracer traces: the mesh with its surface groups, a
 * material per group, the detector and the beam, and the ray queries
 * (Embree 3, behind scene_embree.c, the one file that includes rtcore.h).
 */
#ifndef TRACER_SCENE_H
#define TRACER_SCENE_H

#include <stdbool.h>

#include "stray/error.h"
#include "tracer/brdf.h"
#include "tracer/detector.h"
#include "tracer/mesh.h"
#include "tracer/source.h"

struct tracer_rt;	/* opaque: the Embree device and scene */

/* A reflectance that changes with wavelength (issue 17 item 5): linear
 * between points, held beyond them; n = 0: the material is grey.  The
 * trace runs at the material's rho (the table's mean); the recorded
 * paths are re-weighted photon by photon afterwards (tracer/spectral.h). */
#define TRACER_RHO_TABLE_MAX 64
struct tracer_rho_table {
	int n;
	double nm[TRACER_RHO_TABLE_MAX], rho[TRACER_RHO_TABLE_MAX];
};

struct tracer_scene {
	struct tracer_mesh mesh;
	struct tracer_brdf material[TRACER_GROUP_MAX];	/* per group */
	struct tracer_rho_table spectral[TRACER_GROUP_MAX];	/* per group */
	struct tracer_detector det;
	struct tracer_beam beam;
	struct tracer_rt *rt;		/* set by tracer_scene_commit */
	char note[256];			/* what loading changed ("" none) */
};

struct tracer_hit {
	double t;
	struct vec3 p;		/* hit point, mm */
	struct vec3 ng;		/* unit geometric normal, facing the ray */
	int group;
};

void tracer_scene_init(struct tracer_scene *s);

/* Build the ray-query structure; Embree errors come back through err. */
int tracer_scene_commit(struct tracer_scene *s, struct stray_error *err);

void tracer_scene_free(struct tracer_scene *s);

/* Nearest hit along o + t d, t > 0; false when the ray leaves the scene. */
bool tracer_scene_intersect(const struct tracer_scene *s, struct vec3 o,
			    struct vec3 d, struct tracer_hit *hit);

/* True when something lies on o + t d for 0 < t < tfar (inf allowed). */
bool tracer_scene_occluded(const struct tracer_scene *s, struct vec3 o,
			   struct vec3 d, double tfar);

/* occluded[k] = tracer_scene_occluded(s, o, d[k], INFINITY) for k < n,
 * traced as packets (one origin, n directions). */
void tracer_scene_occluded_fan(const struct tracer_scene *s, struct vec3 o,
			       const struct vec3 *d, size_t n,
			       unsigned char *occluded);

/*
 * A ray origin just off a surface point p on the side of unit normal n,
 * by an epsilon scaled to the magnitude of p (float vertices carry a
 * relative error of FLT_EPSILON; Embree's pathtracer tutorial does the same).
 */
struct vec3 tracer_offset_origin(struct vec3 p, struct vec3 n);

#endif /* TRACER_SCENE_H */
