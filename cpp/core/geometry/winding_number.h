// Generalized winding number of a point with respect to a closed triangle mesh (Jacobson et al. 2013,
// eq. 3; solid angles by van Oosterom and Strackee 1983): ~1 inside, ~0 outside, -1 inside an inward
// mesh, 1/2 on a face (a triangle seen edge-on from its own plane counts 0). The mesh check uses it to
// decide which mesh vertices are inside a cage; cage generation to verify its result.
#pragma once

#include <memory>

#include "core/mesh/mesh.h"

namespace sd {

// The exact sum (std::atan2 per face), O(#faces).
double winding_number(const Mesh& mesh, const Eigen::RowVector3d& p);

// The same sum for many points against one mesh, vectorised: the faces are kept in structure-of-arrays
// blocks and atan2 is a branch-free series (error below 2e-10 rad per face), so classifying a point as
// inside (> 1/2) or outside agrees with winding_number(). About 20 ns per point-face pair natively.
// The faces are read-only after construction and each call works in the caller's Scratch, so threads
// may share one BatchWindingNumber, each with its own Scratch (the mesh-in-cage check does, per block of
// vertices on the thread pool).
class BatchWindingNumber {
 public:
  // The per-face work arrays of one caller, allocated on first use and reused between points.
  class Scratch {
   public:
    Scratch();
    ~Scratch();
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;

   private:
    friend class BatchWindingNumber;
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };

  // `mesh` needs at least one face, finite coordinates and in-range indices.
  explicit BatchWindingNumber(const Mesh& mesh);
  ~BatchWindingNumber();
  BatchWindingNumber(const BatchWindingNumber&) = delete;
  BatchWindingNumber& operator=(const BatchWindingNumber&) = delete;

  double operator()(const Eigen::RowVector3d& p, Scratch& scratch) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sd
