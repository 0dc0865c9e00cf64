#pragma once

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

/// The transform of one <node>: the product of its <matrix> (16 numbers, row-major, acting on
/// column vectors), <translate>, <rotate> (axis, degrees), <scale> and <lookat> children in
/// document order (the first is outermost). Throws naming the element on a wrong number count,
/// a zero rotation axis, or an unsupported <skew>.
DMat4 node_transform(const Document& doc, pugi::xml_node node);

/// `m` applied to a point / a direction, in double precision.
DVec3 transform_point(const DMat4& m, const DVec3& p);
DVec3 transform_vector(const DMat4& m, const DVec3& v);

/// The matrix that maps normals under `m`: the cofactor matrix of m's linear part, with the sign
/// of its determinant. It equals inverse-transpose up to a positive scale and, unlike it, stays
/// finite for singular transforms. Normalize the result.
glm::dmat3 normal_matrix(const DMat4& m);

}  // namespace prism::collada
