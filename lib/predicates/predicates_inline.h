// The filtered fast paths of orient3d and insphere, inline (they sit in the
// per-tet loops, where the call and the exact fallback's stack frame cost more
// than the filter itself). Undecided cases go to the out-of-line exact versions
// in predicates.cpp. Included by predicates.h only.
#pragma once
#include <cfloat>
#include <cmath>

namespace polydual {
namespace detail {

// CGAL's filtered exact predicates (predicates.cpp).
[[gnu::noinline]] Sign orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
[[gnu::noinline]] Sign orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy);
[[gnu::noinline]] Sign insphere_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                      const Point3& e);

// Stage-A static filter of a determinant evaluated in doubles: the sign of
// -det when |det| exceeds bound_factor * perm and perm lies in (tiny, huge)
// (outside it underflow or overflow could spoil the bound); Zero = undecided.
// tiny and huge are literals at the call sites: with -frounding-math (CGAL's
// flag) a division would not be folded at compile time.
inline Sign negated_if_certain(double det, double perm, double bound_factor, double tiny, double huge) {
  if (!(perm > tiny && perm < huge)) return Sign::Zero;
  const double bound = bound_factor * perm;
  if (det > bound) return Sign::Negative;
  if (det < -bound) return Sign::Positive;
  return Sign::Zero;
}

}  // namespace detail

inline Sign orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  // Semi-static filter (Shewchuk's orient3d stage A, errboundA = (7 + 56 eps) eps
  // times the permanent), evaluated on differences to d: det[a-d, b-d, c-d] is
  // -det[b-a, c-a, d-a]. Undecided (or tiny/non-finite magnitudes, where
  // underflow could spoil the bound): CGAL's filtered exact predicate.
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double adz = a.z - d.z, bdz = b.z - d.z, cdz = c.z - d.z;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double perm = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                      (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                      (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
  constexpr double eps = DBL_EPSILON / 2;
  const Sign s = detail::negated_if_certain(det, perm, (7.0 + 56.0 * eps) * eps, 1e-250, 1e250);
  return s != Sign::Zero ? s : detail::orient3d_exact(a, b, c, d);
}

inline Sign orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  // Shewchuk's orient2d stage A (errboundA = (3 + 16 eps) eps times the sum of
  // the two products' magnitudes) on differences to c: the same determinant
  // as det[b-a, c-a]. Undecided, tiny or huge: the exact version.
  const double left = (ax - cx) * (by - cy), right = (ay - cy) * (bx - cx), det = left - right;
  const double sum = std::fabs(left) + std::fabs(right);
  constexpr double eps = DBL_EPSILON / 2;
  const Sign s = detail::negated_if_certain(-det, sum, (3.0 + 16.0 * eps) * eps, 1e-250, 1e250);
  return s != Sign::Zero ? s : detail::orient2d_exact(ax, ay, bx, by, cx, cy);
}

inline Sign insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e) {
  // Semi-static filter: Shewchuk's insphere stage A (errboundA = (16 + 224 eps)
  // eps times the permanent) on differences to e. His determinant is positive
  // for e inside when det[a-d, b-d, c-d] > 0, i.e. for tets that are negative in
  // our convention, so our sign is the opposite of his. Undecided (or tiny or
  // huge magnitudes): CGAL's filtered exact predicate.
  const double aex = a.x - e.x, bex = b.x - e.x, cex = c.x - e.x, dex = d.x - e.x;
  const double aey = a.y - e.y, bey = b.y - e.y, cey = c.y - e.y, dey = d.y - e.y;
  const double aez = a.z - e.z, bez = b.z - e.z, cez = c.z - e.z, dez = d.z - e.z;
  const double aexbey = aex * bey, bexaey = bex * aey, bexcey = bex * cey, cexbey = cex * bey;
  const double cexdey = cex * dey, dexcey = dex * cey, dexaey = dex * aey, aexdey = aex * dey;
  const double aexcey = aex * cey, cexaey = cex * aey, bexdey = bex * dey, dexbey = dex * bey;
  const double ab = aexbey - bexaey, bc = bexcey - cexbey, cd = cexdey - dexcey, da = dexaey - aexdey;
  const double ac = aexcey - cexaey, bd = bexdey - dexbey;
  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;
  const double alift = aex * aex + aey * aey + aez * aez, blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez, dlift = dex * dex + dey * dey + dez * dez;
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  const double aezp = std::fabs(aez), bezp = std::fabs(bez), cezp = std::fabs(cez), dezp = std::fabs(dez);
  const double abp = std::fabs(aexbey) + std::fabs(bexaey), bcp = std::fabs(bexcey) + std::fabs(cexbey);
  const double cdp = std::fabs(cexdey) + std::fabs(dexcey), dap = std::fabs(dexaey) + std::fabs(aexdey);
  const double acp = std::fabs(aexcey) + std::fabs(cexaey), bdp = std::fabs(bexdey) + std::fabs(dexbey);
  const double perm = (cdp * bezp + bdp * cezp + bcp * dezp) * alift + (dap * cezp + acp * dezp + cdp * aezp) * blift +
                      (abp * dezp + bdp * aezp + dap * bezp) * clift + (bcp * aezp + acp * bezp + abp * cezp) * dlift;
  constexpr double eps = DBL_EPSILON / 2;
  const Sign s = detail::negated_if_certain(det, perm, (16.0 + 224.0 * eps) * eps, 1e-200, 1e200);
  return s != Sign::Zero ? s : detail::insphere_exact(a, b, c, d, e);
}

// The summed filter of decomposition_tet_sign(a, b, face, cell, fs, cs)
// (proofs/star_filter.md, L9d), inline for the star test's per-tet loop: the
// EXACT sign when the filter decides, Sign::Zero when it cannot (the caller
// then runs the exact decomposition_tet_sign(a, b, face, cell); Zero is never
// returned as a decided sign). With o the sums' origin and e = fl(a - o),
// s~ = fs.s - k e and t~ = cs.s - m e approximate s = sum(p - a) and
// t = sum(q - a) within (k + 4) eps Sabs and (m + 4) eps Tabs, where
// Sabs = fs.abs + k|e| and Tabs = cs.abs + m|e| bound |s|, |t| (per
// coordinate, up to 1 + (n + 2) eps). det~ = u~.(s~ x t~) then differs from
// the exact det by at most (k + m + 16) eps P, P = |u~|.(Sabs x Tabs); the
// bound takes twice that (and 1 + 1e-6 for the rounding of P).
inline Sign decomposition_tet_sign_if_certain(const Point3& a, const Point3& b, const PointSums& fs,
                                              const PointSums& cs) {
  const double ex = a.x - fs.origin.x, ey = a.y - fs.origin.y, ez = a.z - fs.origin.z;
  const double k = double(fs.n), m = double(cs.n);
  const double sx = fs.sx - k * ex, sy = fs.sy - k * ey, sz = fs.sz - k * ez;
  const double tx = cs.sx - m * ex, ty = cs.sy - m * ey, tz = cs.sz - m * ez;
  const double aex = std::fabs(ex), aey = std::fabs(ey), aez = std::fabs(ez);
  const double asx = fs.ax + k * aex, asy = fs.ay + k * aey, asz = fs.az + k * aez;
  const double atx = cs.ax + m * aex, aty = cs.ay + m * aey, atz = cs.az + m * aez;
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double det = ux * (sy * tz - sz * ty) + uy * (sz * tx - sx * tz) + uz * (sx * ty - sy * tx);
  const double perm = std::fabs(ux) * (asy * atz + asz * aty) + std::fabs(uy) * (asz * atx + asx * atz) +
                      std::fabs(uz) * (asx * aty + asy * atx);
  constexpr double eps = DBL_EPSILON / 2;
  const double bound = 2.0 * (k + m + 16.0) * eps * perm * (1.0 + 1e-6);
  // Below ~1e-250 (or not finite) the bound could be spoiled: undecided.
  if (!(perm > 1e-250 && perm <= DBL_MAX)) return Sign::Zero;
  if (det > bound) return Sign::Negative;  // det > 0  ->  vol(R,a,b,F) < 0
  if (det < -bound) return Sign::Positive;
  return Sign::Zero;
}

inline Sign decomposition_tet_sign(const Point3& a, const Point3& b, std::span<const Point3> face,
                                   std::span<const Point3> cell, const PointSums& fs, const PointSums& cs) {
  // The summed filter, then on doubt the per-tet filter and the exact fallback.
  const Sign s = decomposition_tet_sign_if_certain(a, b, fs, cs);
  return s != Sign::Zero ? s : decomposition_tet_sign(a, b, face, cell);
}

}  // namespace polydual
