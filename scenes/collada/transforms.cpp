#include "scenes/collada/transforms.h"

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace prism::collada {
namespace {

std::vector<double> exactly(const Document& doc, pugi::xml_node element, size_t count) {
  std::vector<double> v = doc.doubles(element);
  if (v.size() != count) {
    doc.fail(element,
             "expected " + std::to_string(count) + " numbers, found " + std::to_string(v.size()));
  }
  return v;
}

}  // namespace

DMat4 up_axis_rotation(const Document& doc) {
  const pugi::xml_node asset = doc.require_child(doc.root(), "asset");
  const pugi::xml_node up = asset.child("up_axis");
  if (!up) doc.fail(asset, "missing <up_axis> (expected X_UP, Y_UP or Z_UP)");
  const std::string_view axis = trimmed_text(up);
  if (axis == "Z_UP") return DMat4(1.0);
  if (axis == "Y_UP") return glm::rotate(DMat4(1.0), glm::radians(90.0), DVec3(1, 0, 0));
  if (axis == "X_UP") return glm::rotate(DMat4(1.0), glm::radians(-90.0), DVec3(0, 1, 0));
  doc.fail(up, "unknown up axis '" + quote(axis) + "' (expected X_UP, Y_UP or Z_UP)");
}

DMat4 node_transform(const Document& doc, pugi::xml_node node,
                     std::vector<ShortMatrix>* short_matrices) {
  DMat4 m(1.0);
  for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
    if (child.type() != pugi::node_element) continue;
    const std::string_view name = child.name();
    if (name == "matrix") {
      std::vector<double> v = doc.doubles(child);
      // The homework streams the numbers into a zero matrix in row order: extra numbers are
      // never read, missing ones stay 0 (an empty <matrix> crashes it).
      if (v.empty()) doc.fail(child, "expected 16 numbers, found 0");
      if (v.size() > 16) {
        doc.warn(child, std::to_string(v.size()) +
                            " numbers, not 16; the numbers after the 16th are ignored, as the "
                            "CS184 homework does");
      } else if (v.size() < 16) {
        short_matrices->push_back({child, v.size()});
      }
      v.resize(16, 0.0);
      DMat4 local;
      // COLLADA lists rows; GLM indexes [column][row].
      for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) local[col][row] = v[4 * row + col];
      }
      m = m * local;
    } else if (name == "translate") {
      const std::vector<double> v = exactly(doc, child, 3);
      m = glm::translate(m, DVec3(v[0], v[1], v[2]));
    } else if (name == "rotate") {
      const std::vector<double> v = exactly(doc, child, 4);
      const DVec3 axis(v[0], v[1], v[2]);
      const double length = glm::length(axis);
      if (!(length > 0.0) || !std::isfinite(length)) doc.fail(child, "rotation axis is zero");
      m = glm::rotate(m, glm::radians(v[3]), axis / length);
    } else if (name == "scale") {
      const std::vector<double> v = exactly(doc, child, 3);
      m = glm::scale(m, DVec3(v[0], v[1], v[2]));
    } else if (name == "lookat") {
      const std::vector<double> v = exactly(doc, child, 9);
      const DVec3 eye(v[0], v[1], v[2]), interest(v[3], v[4], v[5]), up(v[6], v[7], v[8]);
      const DVec3 forward = interest - eye;
      if (glm::length(forward) == 0.0 || glm::length(glm::cross(forward, up)) == 0.0) {
        doc.fail(child,
                 "lookat needs distinct eye and interest points and an up vector that "
                 "is not parallel to the view");
      }
      // glm::lookAt maps world to a view looking down -Z with +Y up: its inverse places the node.
      m = m * glm::inverse(glm::lookAt(eye, interest, up));
    } else if (name == "skew") {
      doc.fail(child, "<skew> transforms are not supported");
    }
  }
  return m;
}

DVec3 transform_point(const DMat4& m, const DVec3& p) {
  const glm::dvec4 q = m * glm::dvec4(p, 1.0);
  // Projective matrices are legal COLLADA; divide when the last row is not (0 0 0 1).
  return (q.w != 1.0 && q.w != 0.0) ? DVec3(q) / q.w : DVec3(q);
}

DVec3 transform_vector(const DMat4& m, const DVec3& v) { return DVec3(m * glm::dvec4(v, 0.0)); }

glm::dmat3 normal_matrix(const DMat4& m) {
  const glm::dmat3 a(m);
  // Columns b x c, c x a, a x b form det(A) * inverse(A)^T.
  glm::dmat3 cofactor(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
  return glm::determinant(a) < 0.0 ? -cofactor : cofactor;
}

}  // namespace prism::collada
