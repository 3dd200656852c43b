/* Friction between simulated surfaces (scene `contact.friction`, or a
 * material's friction), after the iterations, every method: sc_friction_
 * pairs_* per near-list entry, sc_friction per vertex, then sc_apply. Part
 * of contact/self_contact.cl, which includes it at its end (it reads that
 * file's near lists, SC_FOR_EACH_PAIR order, sc_still_apart and the
 * clamps). */
ATS_TASK void sc_apply(int i, __global float4* x, __global const float4* x_out, __global const float4* x_start,
                       __global const float* bound, __global const ats_collider_c* colliders, int collider_count,
                       __global const ats_mesh_near* near) {
  const float4 q = sc_bounded(x_out[i], x_start[i], bound[i]);
  x[i] = sc_out_of_colliders(q, colliders, collider_count, ats_near_of(colliders, collider_count, near, i),
                             sc_moved(q, x[i]));
}

/* Coulomb friction of every pair of vertex i in contact (d < 1.01 r), after
 * the iterations. A pair has two sides, the point and the triangle, or the
 * two edges (weights w_j > 0 and < 0); its relative displacement over the
 * substep is u = sum_j w_j (x_j - x_prev_j), the motion of the first side's
 * point against the second's. Its tangential part is removed whole when it
 * is within mu_s dn (static), else by mu_k dn (kinetic), dn the normal
 * displacement the contact made against the inertial prediction
 * x~ = x_prev + h v (v already holds the substep's gravity),
 * dn = n . sum_j w_j (x_j - x~_j). Each side takes the share of the other
 * side's inverse mass (sum of w_j^2 / m_j over the side), and every vertex of
 * a side moves by its side's share, so that the pair's relative motion loses
 * what Coulomb removes. Vertex i averages its pairs weighted by how hard they
 * press (dn); into x_out (Jacobi).
 * In two steps, as XPBD's projection above: per near-list entry
 * (sc_friction_pairs_*) the pair's friction, evaluated once per list that
 * holds it instead of once by each of its four vertices, into two float4 of
 * the acting pairs only, in list order, then an end mark (dn < 0):
 * (u_t, dn) and (dn * removed, the first side's share, the second side's
 * share, the sides of the four slots as a number: bit j set when w_j > 0,
 * bit 4 + j when w_j < 0); then per vertex (sc_friction) the sum over the
 * acting entries in the order of SC_FOR_EACH_PAIR. Every product is the
 * one-step evaluation's, in the same order, so the bits are too. */
/* The coefficients of one side of a pair: its material's (pf, -1: unset),
 * else the scene's contact.friction (mu). A pair takes the mean of its sides. */
static inline float2 sc_side_mu(float2 pf, float2 mu) { return pf.x < 0.0f ? mu : pf; }

static inline int sc_store_friction(ats_pair_geometry g, const int* pv, __global const float4* x,
                                    __global const float4* x_prev, __global const float4* v, float h, float r,
                                    float mu_s, float mu_k, __global const float2* pf, __global float4* out) {
  /* Touching: XPBD's projection leaves its pairs at d = r exactly. */
  const float touching = 1.01f * r;
  if (!(g.d < touching && g.d > 1e-12f)) return 0;
  const ats_vec3 nrm = ats_pair_normal(g);
  ats_vec3 u = ats_v3(0, 0, 0);
  ats_vec3 push = ats_v3(0, 0, 0);
  float first = 0.0f, second = 0.0f;
  float2 mu_first = (float2)(0.0f), mu_second = (float2)(0.0f);
  int sides = 0;
  for (int j = 0; j < 4; ++j) {
    const float4 xj = x[pv[j]];
    const float4 qj = x_prev[pv[j]];
    const float4 vj = v[pv[j]];
    u = ats_add(u, ats_scale(ats_v3(xj.x - qj.x, xj.y - qj.y, xj.z - qj.z), g.w[j]));
    push = ats_add(push,
                   ats_scale(ats_v3(xj.x - qj.x - h * vj.x, xj.y - qj.y - h * vj.y, xj.z - qj.z - h * vj.z), g.w[j]));
    if (g.w[j] > 0.0f) first += g.w[j] * g.w[j] * xj.w;
    if (g.w[j] < 0.0f) second += g.w[j] * g.w[j] * xj.w;
    if (g.w[j] > 0.0f) mu_first = sc_side_mu(pf[pv[j]], (float2)(mu_s, mu_k));
    if (g.w[j] < 0.0f) mu_second = sc_side_mu(pf[pv[j]], (float2)(mu_s, mu_k));
    if (g.w[j] > 0.0f) sides |= 1 << j;
    if (g.w[j] < 0.0f) sides |= 1 << (4 + j);
  }
  const float dn = ats_dot(push, nrm);
  const ats_vec3 ut = ats_sub(u, ats_scale(nrm, ats_dot(u, nrm)));
  const float len = ats_length(ut);
  if (!(dn > 0.0f && len > 0.0f && first + second > 0.0f)) return 0;
  const float2 mu = 0.5f * (mu_first + mu_second);
  const float removed = len <= mu.x * dn ? 1.0f : fmin(1.0f, mu.y * dn / len);
  out[0] = (float4)(ut.x, ut.y, ut.z, dn);
  out[1] = (float4)(dn * removed, -first / (first + second), second / (first + second), (float)sides);
  return 1;
}

/* After a list's acting entries: an end mark, dn < 0, unless every entry acts. */
static inline void sc_end_friction(int acting, int count, __global float4* out) {
  if (acting < count) out[2 * acting] = (float4)(0.0f, 0.0f, 0.0f, -1.0f);
}
/* List id of `count` near entries, none evaluated (all apart, sc_list_apart). */
static inline void sc_no_friction(int id, int count, __global float4* out, __global int* active) {
  sc_end_friction(0, count, out);
  active[id] = 0;
}

/* The entries of vertex i's near list (as the point of a vertex-triangle pair). */
ATS_TASK void sc_friction_pairs_points(int i, __global const float4* x, __global const float4* x_prev,
                                       __global const float4* v, float h, __global const int4* tris,
                                       __global const int* vt, __global const float* vt_d, __global const float* moved,
                                       __global const float* most, float r, float mu_s, float mu_k,
                                       __global const float2* pf, __global float4* out, __global int* active) {
  __global const int* l = vt + i * ATS_SC_STRIDE;
  __global const float* d0 = vt_d + i * ATS_SC_STRIDE;
  __global float4* o = out + 2 * i * ATS_SC_CAPACITY;
  if (l[0] > 0 && sc_list_apart(d0[0], moved[i], most[0], 1.02f * r)) {
    sc_no_friction(i, l[0], o, active);
    return;
  }
  int k = 0;
  for (int m = 0; m < l[0]; ++m) {
    const int4 f = tris[l[2 + m]];
    const int pv[4] = {i, f.x, f.y, f.z};
    if (sc_still_apart(d0[2 + m], pv, 1, moved, 1.02f * r)) continue;
    const ats_pair_geometry g = ats_point_triangle(sc_v(x[i]), sc_v(x[f.x]), sc_v(x[f.y]), sc_v(x[f.z]));
    k += sc_store_friction(g, pv, x, x_prev, v, h, r, mu_s, mu_k, pf, o + 2 * k);
  }
  sc_end_friction(k, l[0], o);
  active[i] = k;
}

/* The entries of triangle t's near list (the points near it). */
ATS_TASK void sc_friction_pairs_triangles(int t, __global const float4* x, __global const float4* x_prev,
                                          __global const float4* v, float h, __global const int4* tris,
                                          __global const int* tv, __global const float* tv_d,
                                          __global const float* moved, __global const float* most, float r, float mu_s,
                                          float mu_k, __global const float2* pf, __global float4* out,
                                          __global int* active) {
  __global const int* l = tv + t * ATS_SC_STRIDE;
  __global const float* d0 = tv_d + t * ATS_SC_STRIDE;
  const int4 f = tris[t];
  __global float4* o = out + 2 * t * ATS_SC_CAPACITY;
  if (l[0] > 0 && sc_list_apart(d0[0], most[0], sc_side_bound(moved, f.x, f.y, f.z), 1.02f * r)) {
    sc_no_friction(t, l[0], o, active);
    return;
  }
  int k = 0;
  for (int m = 0; m < l[0]; ++m) {
    const int p = l[2 + m];
    const int pv[4] = {p, f.x, f.y, f.z};
    if (sc_still_apart(d0[2 + m], pv, 1, moved, 1.02f * r)) continue;
    const ats_pair_geometry g = ats_point_triangle(sc_v(x[p]), sc_v(x[f.x]), sc_v(x[f.y]), sc_v(x[f.z]));
    k += sc_store_friction(g, pv, x, x_prev, v, h, r, mu_s, mu_k, pf, o + 2 * k);
  }
  sc_end_friction(k, l[0], o);
  active[t] = k;
}

/* The entries of edge e's near list (the edges near it). */
ATS_TASK void sc_friction_pairs_edges(int e, __global const float4* x, __global const float4* x_prev,
                                      __global const float4* v, float h, __global const int2* edges,
                                      __global const int* ee, __global const float* ee_d, __global const float* moved,
                                      __global const float* most, float r, float mu_s, float mu_k,
                                      __global const float2* pf, __global float4* out, __global int* active) {
  __global const int* l = ee + e * ATS_SC_STRIDE;
  __global const float* d0 = ee_d + e * ATS_SC_STRIDE;
  const int2 s = edges[e];
  __global float4* o = out + 2 * e * ATS_SC_CAPACITY;
  if (l[0] > 0 && sc_list_apart(d0[0], sc_side_bound(moved, s.x, s.y, -1), most[0], 1.02f * r)) {
    sc_no_friction(e, l[0], o, active);
    return;
  }
  int k = 0;
  for (int m = 0; m < l[0]; ++m) {
    const int2 q = edges[l[2 + m]];
    const int pv[4] = {s.x, s.y, q.x, q.y};
    if (sc_still_apart(d0[2 + m], pv, 2, moved, 1.02f * r)) continue;
    const ats_pair_geometry g = ats_edge_edge(sc_v(x[s.x]), sc_v(x[s.y]), sc_v(x[q.x]), sc_v(x[q.y]));
    k += sc_store_friction(g, pv, x, x_prev, v, h, r, mu_s, mu_k, pf, o + 2 * k);
  }
  sc_end_friction(k, l[0], o);
  active[e] = k;
}

/* A list's acting entries (up to its end mark) for the vertex in `slot`,
 * added to *sum and *weight. */
static inline void sc_add_friction(__global const float4* e, int count, int slot, ats_vec3* sum, float* weight) {
  for (int m = 0; m < count; ++m, e += 2) {
    const float4 a = e[0];
    if (a.w < 0.0f) break;
    const float4 b = e[1];
    const int sides = (int)b.w;
    if (!(sides & ((1 << slot) | (1 << (4 + slot))))) continue; /* w_slot = 0 */
    /* On the first side i moves against u, on the second with it. */
    const float share = (sides & (1 << slot)) ? b.y : b.z;
    *sum = ats_add(*sum, ats_scale(ats_v3(a.x, a.y, a.z), b.x * share));
    *weight += a.w;
  }
}

/* vt_k, tv_k, ee_k: per list the count of its acting entries (the
 * sc_friction_pairs_* before it), as in sc_project. */
ATS_TASK void sc_friction(int i, __global const float4* x, __global float4* x_out, __global const int4* tris,
                          __global const int2* edges, __global const int* inc, int n, __global const int* vt,
                          __global const float4* vt_f, __global const float4* tv_f, __global const float4* ee_f,
                          __global const int* vt_k, __global const int* tv_k, __global const int* ee_k) {
  const float4 p = x[i];
  x_out[i] = p;
  if (p.w == 0.0f || !sc_is_surface(inc, i) || !(vt[i * ATS_SC_STRIDE + 1] > 0)) return;
  ats_vec3 sum = ats_v3(0, 0, 0);
  float weight = 0.0f;
  if (vt_k[i] > 0) sc_add_friction(vt_f + 2 * i * ATS_SC_CAPACITY, vt_k[i], 0, &sum, &weight);
  for (int k = inc[i]; k < inc[i + 1]; ++k) {
    const int t = inc[k];
    if (tv_k[t] == 0) continue;
    const int4 f = tris[t];
    const int slot = f.x == i ? 1 : (f.y == i ? 2 : 3);
    sc_add_friction(tv_f + 2 * t * ATS_SC_CAPACITY, tv_k[t], slot, &sum, &weight);
  }
  for (int k = inc[n + 1 + i]; k < inc[n + 2 + i]; ++k) {
    const int e = inc[k];
    if (ee_k[e] == 0) continue;
    const int slot = edges[e].x == i ? 0 : 1;
    sc_add_friction(ee_f + 2 * e * ATS_SC_CAPACITY, ee_k[e], slot, &sum, &weight);
  }
  if (!(weight > 0.0f)) return;
  const float s = 1.0f / weight;
  x_out[i] = (float4)(p.x + s * sum.x, p.y + s * sum.y, p.z + s * sum.z, p.w);
}
