#include "scenes/collada/materials.h"

#include <string>
#include <string_view>

namespace prism::collada {
namespace {

void read_color(const Document& doc, pugi::xml_node parent, const char* name, Rgb& field) {
  if (const pugi::xml_node e = parent.child(name)) field = doc.color(e);
}

// A scalar parameter that must be finite and satisfy `valid`; kept at its default when absent.
template <typename Valid>
void read_scalar(const Document& doc, pugi::xml_node parent, const char* name, float& field,
                 Valid valid, const char* requirement) {
  const pugi::xml_node e = parent.child(name);
  if (!e) return;
  const double v = doc.scalar(e);
  if (!valid(v)) doc.fail(e, std::string(name) + " must be " + requirement);
  field = static_cast<float>(v);
}

void parse_cgl(const Document& doc, pugi::xml_node bsdf, Material& m) {
  const auto non_negative = [](double v) { return v >= 0.0; };
  const auto positive = [](double v) { return v > 0.0; };
  const std::string_view type = bsdf.name();
  if (type == "emission") {
    m.type = MaterialType::kEmission;
    read_color(doc, bsdf, "radiance", m.radiance);
  } else if (type == "mirror") {
    m.type = MaterialType::kMirror;
    read_color(doc, bsdf, "reflectance", m.reflectance);
  } else if (type == "glass") {
    m.type = MaterialType::kGlass;
    read_color(doc, bsdf, "reflectance", m.reflectance);
    read_color(doc, bsdf, "transmittance", m.transmittance);
    read_scalar(doc, bsdf, "roughness", m.roughness, non_negative, ">= 0");
    read_scalar(doc, bsdf, "ior", m.ior, positive, "> 0");
  } else if (type == "refraction") {
    m.type = MaterialType::kRefraction;
    read_color(doc, bsdf, "transmittance", m.transmittance);
    read_scalar(doc, bsdf, "roughness", m.roughness, non_negative, ">= 0");
    read_scalar(doc, bsdf, "ior", m.ior, positive, "> 0");
  } else if (type == "microfacet") {
    m.type = MaterialType::kMicrofacet;
    read_scalar(doc, bsdf, "alpha", m.alpha, positive, "> 0");
    read_color(doc, bsdf, "eta", m.eta);
    read_color(doc, bsdf, "k", m.k);
  } else {
    doc.fail(bsdf, "unknown CGL material type <" + quote(type) +
                       "> (expected emission, mirror, glass, refraction or microfacet)");
  }
}

}  // namespace

Material parse_material(const Document& doc, pugi::xml_node material) {
  Material m;
  m.name = material.attribute("name") ? material.attribute("name").value()
                                      : material.attribute("id").value();
  m.type = MaterialType::kDiffuse;
  m.reflectance = Rgb(0.5f);
  const pugi::xml_node effect =
      doc.resolve(doc.require_child(material, "instance_effect"), "url", "effect");
  if (const pugi::xml_node bsdf = first_element(find_extra_technique(effect, "CGL"))) {
    parse_cgl(doc, bsdf, m);
    return m;
  }
  for (pugi::xml_node technique : effect.child("profile_COMMON").children("technique")) {
    for (const char* model : {"phong", "lambert", "blinn"}) {
      const pugi::xml_node color = technique.child(model).child("diffuse").child("color");
      if (color) {
        m.reflectance = doc.color(color);
        return m;
      }
    }
  }
  return m;
}

uint32_t MaterialTable::index_of(pugi::xml_node material) {
  const auto it = indices_.find(material.hash_value());
  if (it != indices_.end()) return it->second;
  materials_.push_back(parse_material(doc_, material));
  const auto index = static_cast<uint32_t>(materials_.size() - 1);
  indices_.emplace(material.hash_value(), index);
  return index;
}

uint32_t MaterialTable::default_index() {
  if (default_ < 0) {
    Material grey;
    grey.name = "default";
    grey.type = MaterialType::kDiffuse;
    grey.reflectance = Rgb(0.5f);
    materials_.push_back(grey);
    default_ = static_cast<int64_t>(materials_.size() - 1);
  }
  return static_cast<uint32_t>(default_);
}

}  // namespace prism::collada
