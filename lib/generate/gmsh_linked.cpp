// gmsh_module::gmsh_api() for programs linked with Gmsh (polydual::generate):
// the table of gmsh_mesher.cpp, in the same binary.
#include "generate/gmsh_module.h"

namespace polydual::gmsh_module {

const GmshApi& gmsh_api() { return *polydual_gmsh_module_api(); }

}  // namespace polydual::gmsh_module
