// A ray through a height-only field along a stretch of heights where it cannot turn. Bouguer's
// invariant n(h) cos e = beta gives the elevation at every height, so the ray's horizontal run
// and path length between two heights are the integrals
//   run = int beta / sqrt(n^2 - beta^2) dh,   length = int n / sqrt(n^2 - beta^2) dh
// (cos e / sin e and 1 / sin e per unit height), smooth while sin e stays well above 0. The
// caster uses them for rays too steep to turn anywhere (its fast path for shadow and bounce
// rays) and for rays that have risen above every object (where they leave the air).
#pragma once

#include "refracta/media/index_field.h"

namespace refracta {

class BouguerBranch {
 public:
  // beta = n(h0) cos e0 of the ray; the field must be height-only and outlive the branch.
  BouguerBranch(const IndexField& field, double beta) : field_(field), beta_(beta) {}

  // n, dn/dh and sin e at height h; false where the ray would be within min_sine of level
  // (at or near a turning height) or the field cannot be evaluated (outside its modelled air).
  bool at(double h, double min_sine, double* n, double* dn, double* sin_e) const;
  // Run and path length from height ha to hb (8-point Gauss-Legendre); false if sin e falls
  // below min_sine at a node. relative_tol > 0: panels are halved until two halves agree with
  // their whole to that fraction of the run and length (a spherical Earth's escapes need the
  // run to metres over thousands of kilometres: it sets the central angle); 0: one panel.
  // absolute_tol [m]: halving also stops where the halves agree to that (shared out by width):
  // the larger of the two tolerances holds.
  bool integrate(double ha, double hb, double min_sine, double* run, double* length, double relative_tol = 0.0,
                 double absolute_tol = 0.0) const;

  // The same with what a caller needs to trust one straight chord over the stretch, given sin e
  // at both ends: `error` estimates the quadrature's error in run and length [m] by its
  // difference from the trapezoid rule over the ends and nodes (large where a layer thinner
  // than the node spacing sits between samples), and `turning` is the total variation of the elevation over the samples
  // [rad] (a chord of length L strays at most L * turning / 4 from a path whose curvature
  // keeps its sign between samples).
  struct Stretch {
    double run = 0.0, length = 0.0, error = 0.0, turning = 0.0;
  };
  bool integrate(double ha, double sin_a, double hb, double sin_b, double min_sine, Stretch* out) const;

  double beta() const { return beta_; }

 private:
  const IndexField& field_;
  double beta_;
};

}  // namespace refracta
