#pragma once

#include <vector>

#include <pugixml.hpp>

#include "core/math.h"
#include "scenes/collada/document.h"

namespace prism::collada {

/// prism's world frame for COLLADA scenes is always Z-up: the loader maps every file into it
/// with a proper rotation chosen by <asset><up_axis> (Z_UP: identity; Y_UP: +90 degrees about X,
/// so +Y -> +Z; X_UP: -90 degrees about Y, so +X -> +Z). Geometry, lights and camera move
/// together, so the image never changes; and because these rotations only permute axes, the
/// axis-aligned bounds used by the homework's camera framing rotate exactly as well.
inline constexpr Vec3 kWorldUp{0.0f, 0.0f, 1.0f};

/// The rotation from the file's frame to the Z-up world. Throws Error(kInput) when <up_axis>
/// is missing or is not X_UP, Y_UP or Z_UP.
DMat4 up_axis_rotation(const Document& doc);

/// A <matrix> with fewer than 16 numbers, found by node_transform().
struct ShortMatrix {
  pugi::xml_node element;
  size_t numbers = 0;  ///< how many numbers it holds (1 to 15)
};

/// The transform of one <node>: the product of its <matrix> (16 numbers, row-major, acting on
/// column vectors), <translate>, <rotate> (axis, degrees), <scale> and <lookat> children in
/// document order (the first is outermost). A <matrix> is read as the CS184 homework reads it,
/// its numbers in row order into a 4x4 of zeros:
/// - more than 16 numbers: the first 16 are the matrix; warns (Document::warn) that the rest
///   are ignored;
/// - 1 to 15 numbers: the missing ones are 0. Whether that is tolerable depends on what the
///   node holds, so each such <matrix> is appended to `*short_matrices` (not null) for the
///   caller to warn about or reject.
/// Throws naming the element on an empty <matrix>, another element with the wrong number
/// count, a zero rotation axis, or an unsupported <skew>.
DMat4 node_transform(const Document& doc, pugi::xml_node node,
                     std::vector<ShortMatrix>* short_matrices);

/// `m` applied to a point / a direction, in double precision.
DVec3 transform_point(const DMat4& m, const DVec3& p);
DVec3 transform_vector(const DMat4& m, const DVec3& v);

/// The matrix that maps normals under `m`: the cofactor matrix of m's linear part, with the sign
/// of its determinant. It equals inverse-transpose up to a positive scale and, unlike it, stays
/// finite for singular transforms. Normalize the result.
glm::dmat3 normal_matrix(const DMat4& m);

}  // namespace prism::collada
