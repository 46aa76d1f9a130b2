// The names of a model's named entities as the writers take them.
#pragma once
#include <cstdint>
#include <map>
#include <string>

namespace polydual {

// The names of the named model entities, by tag (PolyMesh::cell_material for
// regions, PolyMesh::face_tag for faces). Unnamed entities are absent; an
// empty ModelNames writes every output exactly as without names.
struct ModelNames {
  std::map<std::int32_t, std::string> regions;
  std::map<std::int32_t, std::string> faces;
  bool empty() const { return regions.empty() && faces.empty(); }
};

}  // namespace polydual
