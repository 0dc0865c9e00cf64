#include "scenes/mesh_file_loader.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "core/error.h"
#include "core/strings.h"

namespace prism {
namespace {

/// Triangles of one Assimp mesh appended to `out`, with per-corner attributes when wanted.
void append_mesh(const aiMesh& in, bool with_normals, bool with_uvs, TriangleMesh& out) {
  const size_t base = out.positions.size();
  for (unsigned i = 0; i < in.mNumVertices; ++i) {
    const aiVector3D& p = in.mVertices[i];
    out.positions.emplace_back(p.x, p.y, p.z);
  }
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    // SortByPType removed points and lines; anything else that is not a triangle is skipped.
    if (face.mNumIndices != 3) continue;
    const unsigned* idx = face.mIndices;
    out.triangles.emplace_back(static_cast<uint32_t>(base + idx[0]),
                               static_cast<uint32_t>(base + idx[1]),
                               static_cast<uint32_t>(base + idx[2]));
    for (int c = 0; c < 3; ++c) {
      if (with_normals) {
        const aiVector3D& n = in.mNormals[idx[c]];
        out.normals.emplace_back(n.x, n.y, n.z);
      }
      if (with_uvs) {
        const aiVector3D& t = in.mTextureCoords[0][idx[c]];
        out.uvs.emplace_back(t.x, t.y);
      }
    }
  }
}

/// Bytes of a PLY scalar type, or 0 for an unknown name.
size_t ply_type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

size_t count_tokens(const std::string& line, std::vector<std::string>* first_tokens = nullptr,
                    size_t wanted = 0) {
  std::istringstream in(line);
  std::string token;
  size_t n = 0;
  while (in >> token) {
    if (first_tokens && n < wanted) first_tokens->push_back(token);
    ++n;
  }
  return n;
}

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  size_t scalars = 0;           ///< scalar properties
  size_t scalar_bytes = 0;      ///< their size in binary files
  size_t lists = 0;             ///< list properties
  size_t list_count_bytes = 0;  ///< size of their length fields in binary files
  bool list_is_last = false;    ///< the usual layout: scalars, then one list
};

}  // namespace

void check_ply_structure(const std::filesystem::path& path, const ErrorLocation& where) {
  std::ifstream in(path, std::ios::binary);
  const auto fail = [&](int line, const std::string& message) {
    throw Error(ErrorKind::kInput, "invalid PLY file: " + message, {where.file, line, {}});
  };
  constexpr int kMaxHeaderLines = 100000;
  std::string line, format;
  std::vector<PlyElement> elements;
  bool ended = false;
  int number = 0;
  while (!ended && number < kMaxHeaderLines && std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> t;
    count_tokens(line, &t, 6);
    if (number == 1) {
      if (line != "ply") fail(1, "the first line must be 'ply'");
      continue;
    }
    if (t.empty()) fail(number, "empty header line");
    const std::string& key = t[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      ended = true;
    } else if (key == "format") {
      if (t.size() != 3 ||
          (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian")) {
        fail(number, "unknown format line '" + line + "'");
      }
      format = t[1];
    } else if (key == "element") {
      if (t.size() != 3 || t[2].find_first_not_of("0123456789") != std::string::npos ||
          t[2].size() > 18) {
        fail(number, "malformed element line '" + line + "'");
      }
      elements.push_back({t[1], std::stoull(t[2])});
    } else if (key == "property") {
      if (elements.empty()) fail(number, "property before any element");
      PlyElement& e = elements.back();
      if (t.size() == 5 && t[1] == "list") {
        if (ply_type_size(t[2]) == 0 || ply_type_size(t[3]) == 0) {
          fail(number, "unknown property type in '" + line + "'");
        }
        ++e.lists;
        e.list_count_bytes += ply_type_size(t[2]);
        e.list_is_last = e.lists == 1;
      } else if (t.size() == 3 && ply_type_size(t[1]) != 0) {
        ++e.scalars;
        e.scalar_bytes += ply_type_size(t[1]);
        e.list_is_last = false;
      } else {
        fail(number, "malformed property line '" + line + "'");
      }
    } else {
      fail(number, "unexpected header line '" + line + "'");
    }
  }
  if (!ended) fail(0, "the header has no end_header line");
  if (format.empty()) fail(0, "the header has no format line");
  if (format != "ascii") {
    // Binary: every element needs at least its scalars and its list lengths.
    const auto body_start = static_cast<uint64_t>(in.tellg());
    const uint64_t size = std::filesystem::file_size(path);
    long double needed = 0;
    for (const PlyElement& e : elements) {
      needed += static_cast<long double>(e.count) * (e.scalar_bytes + e.list_count_bytes);
    }
    if (static_cast<long double>(size - body_start) < needed) {
      fail(0, "the body is truncated: the header declares at least " +
                  std::to_string(static_cast<uint64_t>(needed)) + " bytes, the file has " +
                  std::to_string(size - body_start));
    }
    return;
  }
  // ASCII: one line per element instance with a value for every property.
  for (const PlyElement& e : elements) {
    for (uint64_t i = 0; i < e.count; ++i) {
      do {
        if (!std::getline(in, line)) {
          fail(number, "the body is truncated: element '" + e.name + "' declares " +
                           std::to_string(e.count) + " entries, the file has " + std::to_string(i));
        }
        ++number;
      } while (line.find_first_not_of(" \t\r") == std::string::npos);
      std::vector<std::string> t;
      const size_t n = count_tokens(line, &t, e.scalars + 1);
      bool ok = n >= e.scalars + e.lists;
      if (ok && e.list_is_last) {
        // The one list's length is the token after the scalars.
        const std::string& length = t[e.scalars];
        ok = length.find_first_not_of("0123456789") == std::string::npos && length.size() < 10 &&
             n == e.scalars + 1 + std::stoull(length);
      }
      if (!ok) fail(number, "element '" + e.name + "' line has the wrong number of values");
    }
  }
}

TriangleMesh load_mesh_file(const std::filesystem::path& path) {
  const ErrorLocation where{path.string(), 0, {}};
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw Error(ErrorKind::kInput, "mesh file not found", where);
  }
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(ErrorKind::kInput, "mesh path is not a regular file", where);
  }
  const std::string ext = lower_case_extension(path);
  if (ext != ".obj" && ext != ".ply") {
    throw Error(ErrorKind::kInput,
                "unsupported mesh file extension '" + ext + "'; supported: .obj, .ply", where);
  }
  try {
    if (ext == ".ply") check_ply_structure(path, where);
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                           aiProcess_PreTransformVertices | aiProcess_SortByPType |
                           aiProcess_ValidateDataStructure;
    const aiScene* scene = importer.ReadFile(path.string(), flags);
    if (scene == nullptr) {
      throw Error(ErrorKind::kInput,
                  std::string("cannot read mesh file: ") + importer.GetErrorString(), where);
    }
    if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
      throw Error(ErrorKind::kInput, "mesh file is incomplete", where);
    }
    size_t vertices = 0, triangles = 0;
    bool all_normals = true, all_uvs = true;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const aiMesh& mesh = *scene->mMeshes[m];
      if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
      vertices += mesh.mNumVertices;
      triangles += mesh.mNumFaces;
      all_normals = all_normals && mesh.HasNormals();
      all_uvs = all_uvs && mesh.HasTextureCoords(0);
    }
    if (triangles == 0) {
      throw Error(ErrorKind::kInput, "mesh file contains no triangles", where);
    }
    if (vertices >= std::numeric_limits<uint32_t>::max()) {
      throw Error(ErrorKind::kInput, "mesh file has more vertices than 32-bit indices address",
                  where);
    }
    TriangleMesh out;
    out.name = path.filename().string();
    out.positions.reserve(vertices + 1);  // +1: Embree's padding, see TriangleMesh::finalize
    out.triangles.reserve(triangles);
    if (all_normals) out.normals.reserve(3 * triangles);
    if (all_uvs) out.uvs.reserve(3 * triangles);
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const aiMesh& mesh = *scene->mMeshes[m];
      if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
      append_mesh(mesh, all_normals, all_uvs, out);
    }
    for (const Vec3& p : out.positions) {
      if (!is_finite(p)) throw Error(ErrorKind::kInput, "vertex position is not finite", where);
    }
    return out;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource, "out of memory while reading mesh file", where);
  }
}

}  // namespace prism
