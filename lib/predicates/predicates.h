// The only place polydual decides signs (docs/design.md, Conventions: exactness lives in one place).
// Every function here is EXACT: it returns the sign of the real-number
// expression of its double inputs, whatever the rounding. Each runs a floating
// point filter first and an exact fallback on dyadic numbers (CGAL::Mpzf) or
// CGAL's filtered Epick predicates when the filter cannot decide.
#pragma once
#include <atomic>
#include <cstdint>
#include <span>

#include "core/vec3.h"

namespace polydual {

enum class Sign : int { Negative = -1, Zero = 0, Positive = 1 };

// Sign of det[b-a, c-a, d-a]: Positive iff d lies on the side of plane (a,b,c)
// that its right-hand normal points to (CGAL::orientation convention).
inline Sign orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// Sign of the insphere determinant of (a,b,c,d) against e, for a positive
// tet (a,b,c,d): Positive iff e is strictly inside the circumsphere, Zero iff
// cospherical.
inline Sign insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e);

// Signs of the barycentric coordinates of the circumcenter of a positive tet
// (a,b,c,d) with respect to its vertices, in that order. The closed tet
// contains its circumcenter iff none is Negative (well-centred, design §4.1).
void circumcenter_barycentric_signs(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d, Sign out[4]);

// The same signs (EXACT), plus what tet_central_point needs in doubles from
// the same products: the rounded circumcenter (returned) and approximations of
// the four barycentric coordinates (lambda, summing to 1; NOT exact).
// If `error` is given and the tet is well-centred (no sign Negative), *error
// bounds max_k |rounded centre_k - exact centre_k| (the exact circumcentre of
// the double inputs; proofs/star_filter.md, L9c); it is +infinity for other
// tets and where no bound is derived (near-flat or extreme magnitudes).
Point3 circumcenter_with_signs(const Point3& a, const Point3& b, const Point3& c, const Point3& d, Sign out[4],
                               double lambda[4], double* error = nullptr);

// Same for a non-degenerate triangle (in its own plane): out[i] is the sign of
// the circumcenter's barycentric coordinate at vertex i, i.e. of the dot product
// of the two edge vectors leaving vertex i (acute, right or obtuse angle).
void triangle_circumcenter_barycentric_signs(const Point3& a, const Point3& b, const Point3& c,
                                             Sign out[3]);

// The star-shaped test's decomposition tet (design §5). With F the mean of
// `face` and R the mean of `cell`, returns the sign of det[a-R, b-R, F-R]
// (signed volume of (R,a,b,F)): Positive is the valid orientation when (a,b) is an
// edge of the face in its outward order. Computed as the sign of
// -det[b-a, sum(p-a), sum(q-a)] (positive scalings dropped), with a static
// filter (proofs/star_filter.md) and an exact Mpzf fallback.
Sign decomposition_tet_sign(const Point3& a, const Point3& b, std::span<const Point3> face,
                            std::span<const Point3> cell);

// Sums of a point set relative to an origin o (a double point, the same for a
// cell and its faces): s = sum fl(p - o), abs = sum |fl(p - o)|, n points.
// Computed once per cell and once per face, they make the first filter of the
// star test O(1) per decomposition tet instead of O(|face| + |cell|).
struct PointSums {
  Point3 origin;
  double sx = 0, sy = 0, sz = 0;
  double ax = 0, ay = 0, az = 0;
  std::size_t n = 0;
};
PointSums point_sums(std::span<const Point3> pts, const Point3& origin);

// EXACT, the same sign as decomposition_tet_sign(a, b, face, cell): a first
// static filter from the sums (fs of face, cs of cell, both about one origin;
// proofs/star_filter.md, L9d), then on doubt decomposition_tet_sign itself
// (its own filter, then exact).
inline Sign decomposition_tet_sign(const Point3& a, const Point3& b, std::span<const Point3> face,
                                   std::span<const Point3> cell, const PointSums& fs, const PointSums& cs);

// The same expression in plain doubles: NOT exact. For benchmarks and for the
// adversarial tests that show why the exact version exists.
Sign decomposition_tet_sign_inexact(const Point3& a, const Point3& b, std::span<const Point3> face,
                                    std::span<const Point3> cell);

// The surface dual's fan test (design §15): the sign of n . ((p - r) x (q - r)),
// i.e. of orient3d(r, p, q, r + n) without rounding r + n. Positive iff
// (r, p, q) turns counterclockwise seen from the side n points to. EXACT for
// the given doubles (interval filter, exact Mpzf fallback); n is a direction
// the caller constructed in floating point (a primal cell's normal), so the
// decision is exact given that direction. For r, p, q in a plane z = const
// and n = (0, 0, k), k > 0, it equals orient2d of their (x, y) exactly.
Sign surface_turn(const Point3& r, const Point3& p, const Point3& q, const Vec3& n);

// --- For the input's self-overlap check (classify/self_overlap.h). Triangles
// must be non-degenerate and segments of positive length (the callers pass
// faces and edges of positively oriented tets).

// Sign of det[b-a, c-a] for points of a plane given by two coordinates:
// Positive iff (a, b, c) turn counterclockwise. Shewchuk's stage-A static
// filter, then an interval filter and an exact Mpzf fallback. Applied to two
// coordinates of 3D points, it decides orientations inside a coordinate plane
// exactly (dropping the third coordinate is exact).
inline Sign orient2d(double ax, double ay, double bx, double by, double cx, double cy);

// Sign of orient3d(a, b, c, g) for g = (p + q + r) / 3, the centroid of the
// triangle (p, q, r), without rounding g: the sign of
// det[b-a, c-a, (p-a) + (q-a) + (r-a)] (interval filter, exact Mpzf fallback).
Sign orient3d_centroid(const Point3& a, const Point3& b, const Point3& c, const Point3& p, const Point3& q,
                       const Point3& r);

// For coplanar a, b, c, d, a, b, c not collinear: Positive iff c and d lie on
// the same side of the line ab in their plane, Zero iff d lies on that line,
// Negative iff on opposite sides (CGAL::coplanar_orientation).
Sign coplanar_orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// Whether the closed segment [p, q] and the closed triangle (a, b, c) have a
// point in common (CGAL's do_intersect on the filtered Epick kernel).
bool segment_meets_triangle(const Point3& p, const Point3& q, const Point3& a, const Point3& b, const Point3& c);

// Whether the closed triangles (a, b, c) and (p, q, r) have a point in common.
bool triangles_meet(const Point3& a, const Point3& b, const Point3& c, const Point3& p, const Point3& q,
                    const Point3& r);

// How often the exact paths ran (relaxed atomics; for reports and benchmarks).
// Only the rare exact fallbacks touch these shared counters: the callers know
// how many predicates they evaluated (no contended write on the hot path).
struct PredicateCounters {
  std::atomic<std::uint64_t> star_exact{0};
  std::atomic<std::uint64_t> circ_exact{0};
  std::atomic<std::uint64_t> overlap_exact{0};   // orient2d, orient3d_centroid
  std::atomic<std::uint64_t> surface_exact{0};   // surface_turn
  void reset() { star_exact = circ_exact = overlap_exact = surface_exact = 0; }
};
PredicateCounters& predicate_counters();
// The star_exact fallbacks of the calling thread alone (never reset): a caller
// that evaluates one cell at a time on a thread reads the difference around
// it to learn that cell's count (split/recheck.h carries it with the verdict).
std::uint64_t star_exact_this_thread();

}  // namespace polydual

#include "predicates/predicates_inline.h"
