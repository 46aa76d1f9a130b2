// The boundary between polydual and Gmsh. Everything that calls Gmsh (and so
// loads libgmsh and OpenCASCADE, ~100 shared libraries and ~0.1 s at start-up)
// lives behind this table of functions, in gmsh_mesher.cpp. The library
// polydual::generate links it directly; the polydual command builds it as a
// module (polydual-gmsh.so) that only `generate` and `demo` load with dlopen
// (gmsh_module_loader.cpp), so that every other command starts without Gmsh.
//
// The table passes plain data only (no polydual types, no exceptions across
// it): the module depends on Gmsh and the C++ runtime alone, and a stale
// module is refused by its ABI version instead of misbehaving.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace polydual::gmsh_module {

// Bump whenever GmshApi, RawMesh or the meaning of a domain number changes.
inline constexpr int kAbiVersion = 3;

// The domains by number (generate/domains.h's Domain, in its order).
inline constexpr int kNumDomains = 8;

// A Gmsh mesh as Gmsh gives it: nodes with their tags and coordinates, and
// the elements of each model entity, entities sorted by (dim, tag).
struct RawBlock {
  int dim = 0;                     // 3 tets, 2 triangles, 1 segments, 0 points
  int tag = 0;                     // the model entity
  std::vector<std::size_t> nodes;  // node tags, 4/3/2/1 per element
};
struct RawMesh {
  std::vector<std::size_t> node_tags;
  std::vector<double> coords;  // 3 per node, in node_tags' order
  std::vector<RawBlock> blocks;
};

// Each function returns true on success; on failure it returns false with a
// message in `error` (what Gmsh or the CAD check reported).
struct GmshApi {
  int abi_version;
  // Meshes domain number `domain` with about `target_tets` tets (tet domains
  // only: the layers and dfn domains are refused with a message).
  bool (*mesh)(int domain, std::size_t target_tets, RawMesh& out, std::string& error);
  // The same mesh written by Gmsh's msh 4.1 ASCII writer to `path` (which
  // must end in ".msh": Gmsh picks the format from the extension).
  bool (*write_msh)(int domain, std::size_t target_tets, const char* path, std::string& error);
};

// The table: linked in (polydual::generate) or loaded from polydual-gmsh.so
// (the command). The loader throws std::runtime_error naming the places it
// looked in when the module is missing, cannot be loaded or is stale.
const GmshApi& gmsh_api();

}  // namespace polydual::gmsh_module

// The module's one exported symbol (also defined when linked in).
extern "C" const polydual::gmsh_module::GmshApi* polydual_gmsh_module_api();
