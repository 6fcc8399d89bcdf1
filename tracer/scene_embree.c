/*
 * scene_embree.c - the ray queries on Embree 3 (API pinned to 3.13.x; the
 * only file that includes rtcore.h).  Order as in Embree's minimal
 * tutorial: device, error callback, geometry buffers, commit, attach,
 * release, robust scene commit.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "tracer/scene.h"

#if RTC_VERSION_MAJOR != 3
#error "the tracer is written against the Embree 3 API"
#endif

/* Origin offset in units of FLT_EPSILON * |p|: far above the few ulps of
 * a float hit point, far below any feature (knife-edge radii of ~10 um). */
#define OFFSET_ULPS 256.0

struct tracer_rt {
	RTCDevice device;
	RTCScene scene;
	struct stray_error *err;	/* where the error callback writes */
};

static void on_embree_error(void *user, enum RTCError code, const char *msg)
{
	struct tracer_rt *rt = user;

	(void)msg;
	stray_error_set_value(rt->err, code == RTC_ERROR_OUT_OF_MEMORY ?
			      STRAY_ENOMEM : STRAY_EINVAL, "embree",
			      "ray-tracing kernel reported an error", code);
}

void tracer_scene_init(struct tracer_scene *s)
{
	memset(s, 0, sizeof(*s));
	tracer_mesh_init(&s->mesh);
}

static int attach_mesh(struct tracer_rt *rt, const struct tracer_mesh *m)
{
	RTCGeometry geom = rtcNewGeometry(rt->device, RTC_GEOMETRY_TYPE_TRIANGLE);
	float *v;
	unsigned *idx;

	if (!geom)
		return -1;
	v = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
				    RTC_FORMAT_FLOAT3, 3 * sizeof(float),
				    m->n_vert);
	idx = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
				      RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
				      m->n_tri);
	if (v && idx) {
		memcpy(v, m->vert, m->n_vert * 3 * sizeof(float));
		memcpy(idx, m->tri, m->n_tri * 3 * sizeof(unsigned));
	}
	rtcCommitGeometry(geom);
	/* geomID 0: primID indexes mesh->group directly. */
	rtcAttachGeometry(rt->scene, geom);
	rtcReleaseGeometry(geom);
	return 0;
}

int tracer_scene_commit(struct tracer_scene *s, struct stray_error *err)
{
	struct tracer_rt *rt;

	if (s->mesh.n_tri == 0)
		return stray_error_set(err, STRAY_EINVAL, "scene",
				       "has no triangles");
	rt = calloc(1, sizeof(*rt));
	if (!rt)
		return stray_error_set(err, STRAY_ENOMEM, "scene",
				       "out of memory");
	rt->err = err;
	rt->device = rtcNewDevice(NULL);
	if (!rt->device) {
		free(rt);
		return stray_error_set_value(err, STRAY_EINVAL, "embree",
					     "cannot create device",
					     rtcGetDeviceError(NULL));
	}
	rtcSetDeviceErrorFunction(rt->device, on_embree_error, rt);
	rt->scene = rtcNewScene(rt->device);
	/* Robust: no leaks through shared edges at knife edges and tips. */
	rtcSetSceneFlags(rt->scene, RTC_SCENE_FLAG_ROBUST);
	rtcSetSceneBuildQuality(rt->scene, RTC_BUILD_QUALITY_HIGH);
	attach_mesh(rt, &s->mesh);
	rtcCommitScene(rt->scene);
	s->rt = rt;
	if (err && err->code) {
		tracer_scene_free(s);
		return err->code;
	}
	rt->err = NULL;		/* err is the caller's; do not keep it */
	return STRAY_OK;
}

void tracer_scene_free(struct tracer_scene *s)
{
	if (s->rt) {
		if (s->rt->scene)
			rtcReleaseScene(s->rt->scene);
		rtcReleaseDevice(s->rt->device);
		free(s->rt);
		s->rt = NULL;
	}
	tracer_mesh_free(&s->mesh);
}

static void fill_ray(struct RTCRay *r, struct vec3 o, struct vec3 d, double tfar)
{
	r->org_x = (float)o.x;
	r->org_y = (float)o.y;
	r->org_z = (float)o.z;
	r->dir_x = (float)d.x;
	r->dir_y = (float)d.y;
	r->dir_z = (float)d.z;
	r->tnear = 0.0f;
	r->tfar = isinf(tfar) ? INFINITY : (float)tfar;
	r->time = 0.0f;
	r->mask = 0xFFFFFFFFu;
	r->id = 0;
	r->flags = 0;
}

bool tracer_scene_intersect(const struct tracer_scene *s, struct vec3 o,
			    struct vec3 d, struct tracer_hit *hit)
{
	struct RTCIntersectContext ctx;
	struct RTCRayHit rh;
	struct vec3 ng;

	rtcInitIntersectContext(&ctx);
	ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
	fill_ray(&rh.ray, o, d, INFINITY);
	rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
	rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
	rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
	rtcIntersect1(s->rt->scene, &ctx, &rh);
	if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
		return false;
	hit->t = rh.ray.tfar;
	hit->p = v3_add(o, v3_scale(d, hit->t));
	ng = v3_norm(v3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
	hit->ng = v3_dot(ng, d) > 0.0 ? v3_scale(ng, -1.0) : ng;
	hit->group = s->mesh.group[rh.hit.primID];
	return true;
}

bool tracer_scene_occluded(const struct tracer_scene *s, struct vec3 o,
			   struct vec3 d, double tfar)
{
	struct RTCIntersectContext ctx;
	struct RTCRay r;

	rtcInitIntersectContext(&ctx);
	ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
	fill_ray(&r, o, d, tfar);
	rtcOccluded1(s->rt->scene, &ctx, &r);
	return r.tfar == -INFINITY;	/* Embree marks a hit with -inf */
}

/* One packet of up to W lanes: RTCRay4/8/16 share one layout. */
#define FILL_PACKET(r, W, o, d, m, valid)				\
	do {								\
		size_t k_;						\
		for (k_ = 0; k_ < (W); k_++) {				\
			struct vec3 dk_ = (d)[k_ < (m) ? k_ : 0];	\
			(valid)[k_] = k_ < (m) ? -1 : 0;		\
			(r).org_x[k_] = (float)(o).x;			\
			(r).org_y[k_] = (float)(o).y;			\
			(r).org_z[k_] = (float)(o).z;			\
			(r).dir_x[k_] = (float)dk_.x;			\
			(r).dir_y[k_] = (float)dk_.y;			\
			(r).dir_z[k_] = (float)dk_.z;			\
			(r).tnear[k_] = 0.0f;				\
			(r).tfar[k_] = INFINITY;			\
			(r).time[k_] = 0.0f;				\
			(r).mask[k_] = 0xFFFFFFFFu;			\
			(r).id[k_] = 0;					\
			(r).flags[k_] = 0;				\
		}							\
	} while (0)

/*
 * Shadow rays sharing one origin, in packets of 16 (the last one 4, 8 or
 * 16 wide, a single ray alone): the next-event connections of one vertex
 * to every angle of the sweep, the most coherent rays the tracer casts.
 * The same float ray as tracer_scene_occluded, lane by lane; Embree's
 * packet kernels decide hit or miss per ray (robust scene: the same
 * decisions, checked by bench_trace and the byte-identical curves).
 */
void tracer_scene_occluded_fan(const struct tracer_scene *s, struct vec3 o,
			       const struct vec3 *d, size_t n,
			       unsigned char *occluded)
{
	struct RTCIntersectContext ctx;
	size_t k0, k;

	rtcInitIntersectContext(&ctx);
	ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
	for (k0 = 0; k0 < n; k0 += 16) {
		size_t m = n - k0 < 16 ? n - k0 : 16;
		/* Embree reads the mask as one vector: aligned like the
		 * widest packet (64 bytes), or rtcOccluded16 faults */
		RTC_ALIGN(64) int valid[16];

		/* the narrowest packet that holds the rest */
		if (m == 1) {
			occluded[k0] = tracer_scene_occluded(s, o, d[k0],
							     INFINITY);
		} else if (m <= 4) {
			struct RTCRay4 r;

			FILL_PACKET(r, 4, o, d + k0, m, valid);
			rtcOccluded4(valid, s->rt->scene, &ctx, &r);
			for (k = 0; k < m; k++)
				occluded[k0 + k] = r.tfar[k] == -INFINITY;
		} else if (m <= 8) {
			struct RTCRay8 r;

			FILL_PACKET(r, 8, o, d + k0, m, valid);
			rtcOccluded8(valid, s->rt->scene, &ctx, &r);
			for (k = 0; k < m; k++)
				occluded[k0 + k] = r.tfar[k] == -INFINITY;
		} else {
			struct RTCRay16 r;

			FILL_PACKET(r, 16, o, d + k0, m, valid);
			rtcOccluded16(valid, s->rt->scene, &ctx, &r);
			for (k = 0; k < m; k++)
				occluded[k0 + k] = r.tfar[k] == -INFINITY;
		}
	}
}

struct vec3 tracer_offset_origin(struct vec3 p, struct vec3 n)
{
	double m = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
	double eps = OFFSET_ULPS * FLT_EPSILON * fmax(m, 1.0);

	return v3_add(p, v3_scale(n, eps));
}
