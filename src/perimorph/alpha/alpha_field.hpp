#pragma once
// The morphing field α(x) ∈ [0, 1] (THEORY §3, §3.1): 0 purely local, 1
// purely non-local. A field is a constant (α ≡ 0 or α ≡ 1) or the union
// (pointwise max) of morphing regions; each region is a shape whose inside has
// α = 1, surrounded by a transition of width L in which α = profile(t), with
// t = 1 − d/L the normalized distance (d the distance to the shape, t = 0 at
// the outer border).

#include "perimorph/core/types.hpp"

#include <limits>
#include <variant>
#include <vector>

namespace perimorph::alpha {

enum class Profile { heaviside, linear, cubic };

/// α(t) of THEORY §3.1: heaviside 0 for t < 1/2 else 1; linear t; cubic 3t² − 2t³.
double profile_value(Profile p, double t);

/// [lower, upper] along x (1D).
struct Interval {
  double lower = 0.0, upper = 0.0;
};
/// Points with |n·(x − point)| ≤ half_width.
struct Slab {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitX();  ///< normalized on construction of the field
  double half_width = 0.0;
};
/// Disk (2D) or sphere (3D).
struct Ball {
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
};
/// Infinite cylinder: points within `radius` of the line point + t·axis.
struct Cylinder {
  Vec3 point = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
  double radius = 0.0;
};
/// Axis-aligned box; infinite bounds allowed (a half-space, a slab, ...).
struct Box {
  Vec3 lower = Vec3::Constant(-std::numeric_limits<double>::infinity());
  Vec3 upper = Vec3::Constant(std::numeric_limits<double>::infinity());
};

using Shape = std::variant<Interval, Slab, Ball, Cylinder, Box>;

/// Euclidean distance from x to the shape (0 inside), in the first `dim` coordinates.
double distance(const Shape& shape, const Vec3& x, int dim);

struct Region {
  Shape shape;
  double transition = 0.0;  ///< L ≥ 0 (0: a sharp edge)
  Profile profile = Profile::cubic;
};

/// α of one region at x: 1 inside the shape, profile(1 − d/L) at a distance
/// d < L outside it, 0 beyond (normal and axis of the shape already unit).
double region_value(const Region& region, const Vec3& x, int dim);

class AlphaField {
 public:
  /// α ≡ value everywhere (0 or 1, or any constant in [0, 1]).
  static AlphaField constant(double value);
  /// α = max over the regions (0 outside all of them).
  static AlphaField regions(std::vector<Region> regions, int dim);

  /// A field exactly as region_list(), dim() and constant_value() describe it
  /// (normals and axes taken as they are: a checkpoint, run/checkpoint.hpp).
  static AlphaField exactly(double constant, int dim, std::vector<Region> regions);
  /// This field with `added` regions joined (pointwise max): α never
  /// decreases (THEORY §5, adaptive zone). α ≡ 0 grows into the regions; a
  /// constant α > 0 cannot grow (an error).
  AlphaField grown(std::vector<Region> added, int dim) const;

  double operator()(const Vec3& x) const;
  bool is_constant() const { return regions_.empty(); }
  /// The regions as given to regions(), normals and axes normalized.
  const std::vector<Region>& region_list() const { return regions_; }
  int dim() const { return dim_; }
  double constant_value() const { return constant_; }

 private:
  double constant_ = 0.0;
  int dim_ = 3;
  std::vector<Region> regions_;
};

}  // namespace perimorph::alpha
