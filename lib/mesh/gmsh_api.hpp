#pragma once
// Internal to lib/mesh: how the project reaches Gmsh without every program loading it at start.
//
// Debian builds libgmsh and OpenCASCADE's libraries with BIND_NOW, so a program linked with libgmsh
// resolves ~142,600 symbols in 91 libraries before main: 0.11-0.12 s at every start (PERFORMANCE.md),
// paid by each of the ~400 test processes CTest starts and by every study, though few of them mesh.
// So no program links libgmsh. The Gmsh API functions the project calls (the list below) are defined
// in gmsh_api.cpp as forwarders with the signatures of <gmsh.h>; the first call loads the plugin
// libfem_gmsh.so (plugin/fem_gmsh.cpp, linked with libgmsh) with dlopen and takes the real functions'
// addresses from it. Calls, default arguments and exceptions (Gmsh's API throws its last error
// message as a std::string) are those of Gmsh's C++ API: the forwarder passes everything through.
//
// A Gmsh function not in the list fails to link ("undefined reference to gmsh::..."): add it to
// FEM_GMSH_FUNCTIONS and give it a forwarder in gmsh_api.cpp.
#include <gmsh.h>

// X(member, function): every Gmsh function the project calls (53 of the API's ~300).
#define FEM_GMSH_FUNCTIONS(X) \
    X(clear, gmsh::clear) \
    X(finalize, gmsh::finalize) \
    X(initialize, gmsh::initialize) \
    X(logger_get, gmsh::logger::get) \
    X(logger_start, gmsh::logger::start) \
    X(logger_stop, gmsh::logger::stop) \
    X(merge, gmsh::merge) \
    X(model_add, gmsh::model::add) \
    X(model_addPhysicalGroup, gmsh::model::addPhysicalGroup) \
    X(model_getClosestPoint, gmsh::model::getClosestPoint) \
    X(model_getEntities, gmsh::model::getEntities) \
    X(model_getEntitiesForPhysicalGroup, gmsh::model::getEntitiesForPhysicalGroup) \
    X(model_getEntitiesInBoundingBox, gmsh::model::getEntitiesInBoundingBox) \
    X(model_getPhysicalGroups, gmsh::model::getPhysicalGroups) \
    X(model_getPhysicalName, gmsh::model::getPhysicalName) \
    X(model_mesh_clear, gmsh::model::mesh::clear) \
    X(model_mesh_embed, gmsh::model::mesh::embed) \
    X(model_mesh_field_add, gmsh::model::mesh::field::add) \
    X(model_mesh_field_setAsBackgroundMesh, gmsh::model::mesh::field::setAsBackgroundMesh) \
    X(model_mesh_field_setNumber, gmsh::model::mesh::field::setNumber) \
    X(model_mesh_field_setNumbers, gmsh::model::mesh::field::setNumbers) \
    X(model_mesh_generate, gmsh::model::mesh::generate) \
    X(model_mesh_getElementProperties, gmsh::model::mesh::getElementProperties) \
    X(model_mesh_getElements, gmsh::model::mesh::getElements) \
    X(model_mesh_getNodes, gmsh::model::mesh::getNodes) \
    X(model_mesh_getNodesForPhysicalGroup, gmsh::model::mesh::getNodesForPhysicalGroup) \
    X(model_mesh_setOrder, gmsh::model::mesh::setOrder) \
    X(model_mesh_setTransfiniteAutomatic, gmsh::model::mesh::setTransfiniteAutomatic) \
    X(model_mesh_setTransfiniteCurve, gmsh::model::mesh::setTransfiniteCurve) \
    X(model_occ_addBox, gmsh::model::occ::addBox) \
    X(model_occ_addCylinder, gmsh::model::occ::addCylinder) \
    X(model_occ_addDisk, gmsh::model::occ::addDisk) \
    X(model_occ_addEllipse, gmsh::model::occ::addEllipse) \
    X(model_occ_addLine, gmsh::model::occ::addLine) \
    X(model_occ_addPoint, gmsh::model::occ::addPoint) \
    X(model_occ_addRectangle, gmsh::model::occ::addRectangle) \
    X(model_occ_addSphere, gmsh::model::occ::addSphere) \
    X(model_occ_addThruSections, gmsh::model::occ::addThruSections) \
    X(model_occ_addWire, gmsh::model::occ::addWire) \
    X(model_occ_cut, gmsh::model::occ::cut) \
    X(model_occ_dilate, gmsh::model::occ::dilate) \
    X(model_occ_extrude, gmsh::model::occ::extrude) \
    X(model_occ_fuse, gmsh::model::occ::fuse) \
    X(model_occ_getCenterOfMass, gmsh::model::occ::getCenterOfMass) \
    X(model_occ_getMass, gmsh::model::occ::getMass) \
    X(model_occ_getMatrixOfInertia, gmsh::model::occ::getMatrixOfInertia) \
    X(model_occ_intersect, gmsh::model::occ::intersect) \
    X(model_occ_rotate, gmsh::model::occ::rotate) \
    X(model_occ_synchronize, gmsh::model::occ::synchronize) \
    X(model_occ_translate, gmsh::model::occ::translate) \
    X(model_setPhysicalName, gmsh::model::setPhysicalName) \
    X(option_setNumber, gmsh::option::setNumber) \
    X(write, gmsh::write)

namespace fem::detail {

/// The Gmsh functions' addresses, as the plugin hands them over. `size` is sizeof(GmshApi) of the
/// plugin's build, so that a plugin from an older build is refused rather than called wrongly.
struct GmshApi {
    std::size_t size;
#define FEM_GMSH_MEMBER(member, function) decltype(&function) member;
    FEM_GMSH_FUNCTIONS(FEM_GMSH_MEMBER)
#undef FEM_GMSH_MEMBER
};

/// Where the build put libfem_gmsh.so (gmsh_plugin_path.cpp).
const char* gmsh_plugin_path();

/// The plugin's functions, loaded on the first call (thread-safe). std::runtime_error naming the
/// plugin and dlerror() when it cannot be loaded.
const GmshApi& gmsh_api();

}  // namespace fem::detail

/// The plugin's one exported symbol.
extern "C" const fem::detail::GmshApi* fem_gmsh_api();
