// libfem_gmsh.so: the one piece of the project linked with libgmsh (mesh/gmsh_api.hpp says why).
// Loaded with dlopen by the first Gmsh call of a program; it hands over the addresses of the Gmsh
// functions the project calls.
#include "mesh/gmsh_api.hpp"

extern "C" __attribute__((visibility("default"))) const fem::detail::GmshApi* fem_gmsh_api() {
    static const fem::detail::GmshApi api{
        sizeof(fem::detail::GmshApi),
#define FEM_GMSH_ADDRESS(member, function) &function,
        FEM_GMSH_FUNCTIONS(FEM_GMSH_ADDRESS)
#undef FEM_GMSH_ADDRESS
    };
    return &api;
}
