#include "mesh/gmsh_api.hpp"

namespace fem::detail {

const char* gmsh_plugin_path() { return FEM_GMSH_PLUGIN; }

}  // namespace fem::detail
