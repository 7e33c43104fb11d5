#include "mesh/gmsh_api.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace fem::detail {

namespace {
std::string load_error() {
    const char* e = dlerror();
    return e ? e : "no reason given";
}
}  // namespace

const GmshApi& gmsh_api() {
    // Loaded once and never unloaded (Gmsh keeps global state); a failed load throws and the next
    // call tries again.
    static const GmshApi* const api = [] {
        const char* const plugin_path = gmsh_plugin_path();
        void* plugin = dlopen(plugin_path, RTLD_NOW | RTLD_LOCAL);
        if (!plugin)
            throw std::runtime_error(fmt::format("cannot load the Gmsh plugin {} (built with the project; "
                                                 "mesh/gmsh_api.hpp): {}", plugin_path, load_error()));
        const auto get = reinterpret_cast<const GmshApi* (*)()>(dlsym(plugin, "fem_gmsh_api"));
        if (!get) throw std::runtime_error(fmt::format("{} has no fem_gmsh_api: {}", plugin_path, load_error()));
        const GmshApi* a = get();
        if (a->size != sizeof(GmshApi))
            throw std::runtime_error(fmt::format("{} is from another build of the project (its Gmsh table has {} bytes, "
                                                 "this program's {}): build again", plugin_path, a->size, sizeof(GmshApi)));
        // A program that exported its own symbols (-rdynamic) would have handed the plugin these
        // forwarders in place of Gmsh's functions, and each call would recurse forever.
        if (a->model_add == &gmsh::model::add)
            throw std::runtime_error(fmt::format("{} resolved Gmsh's functions to this program's forwarders (a program "
                                                 "linked with -rdynamic?)", plugin_path));
        return a;
    }();
    return *api;
}

}  // namespace fem::detail

// The forwarders: Gmsh's C++ API as <gmsh.h> declares it (default arguments there), each call passed
// to the plugin's function. A signature that does not match <gmsh.h> is a compile error.
using fem::detail::gmsh_api;

void gmsh::clear() { gmsh_api().clear(); }
void gmsh::finalize() { gmsh_api().finalize(); }
void gmsh::initialize(int argc, char** argv, const bool readConfigFiles) {
    gmsh_api().initialize(argc, argv, readConfigFiles);
}
void gmsh::logger::get(std::vector<std::string>& log) { gmsh_api().logger_get(log); }
void gmsh::logger::start() { gmsh_api().logger_start(); }
void gmsh::logger::stop() { gmsh_api().logger_stop(); }
void gmsh::merge(const std::string& fileName) { gmsh_api().merge(fileName); }
void gmsh::model::add(const std::string& name) { gmsh_api().model_add(name); }
int gmsh::model::addPhysicalGroup(const int dim, const std::vector<int>& tags, const int tag) {
    return gmsh_api().model_addPhysicalGroup(dim, tags, tag);
}
void gmsh::model::getClosestPoint(const int dim, const int tag, const std::vector<double>& coord,
                                  std::vector<double>& closestCoord, std::vector<double>& parametricCoord) {
    gmsh_api().model_getClosestPoint(dim, tag, coord, closestCoord, parametricCoord);
}
void gmsh::model::getEntities(gmsh::vectorpair& dimTags, const int dim) { gmsh_api().model_getEntities(dimTags, dim); }
void gmsh::model::getEntitiesForPhysicalGroup(const int dim, const int tag, std::vector<int>& tags) {
    gmsh_api().model_getEntitiesForPhysicalGroup(dim, tag, tags);
}
void gmsh::model::getEntitiesInBoundingBox(const double xmin, const double ymin, const double zmin, const double xmax,
                                           const double ymax, const double zmax, gmsh::vectorpair& tags,
                                           const int dim) {
    gmsh_api().model_getEntitiesInBoundingBox(xmin, ymin, zmin, xmax, ymax, zmax, tags, dim);
}
void gmsh::model::getPhysicalGroups(gmsh::vectorpair& dimTags, const int dim) {
    gmsh_api().model_getPhysicalGroups(dimTags, dim);
}
void gmsh::model::getPhysicalName(const int dim, const int tag, std::string& name) {
    gmsh_api().model_getPhysicalName(dim, tag, name);
}
void gmsh::model::mesh::clear(const gmsh::vectorpair& dimTags) { gmsh_api().model_mesh_clear(dimTags); }
void gmsh::model::mesh::embed(const int dim, const std::vector<int>& tags, const int inDim, const int inTag) {
    gmsh_api().model_mesh_embed(dim, tags, inDim, inTag);
}
int gmsh::model::mesh::field::add(const std::string& fieldType, const int tag) {
    return gmsh_api().model_mesh_field_add(fieldType, tag);
}
void gmsh::model::mesh::field::setAsBackgroundMesh(const int tag) {
    gmsh_api().model_mesh_field_setAsBackgroundMesh(tag);
}
void gmsh::model::mesh::field::setNumber(const int tag, const std::string& option, const double value) {
    gmsh_api().model_mesh_field_setNumber(tag, option, value);
}
void gmsh::model::mesh::field::setNumbers(const int tag, const std::string& option, const std::vector<double>& value) {
    gmsh_api().model_mesh_field_setNumbers(tag, option, value);
}
void gmsh::model::mesh::generate(const int dim) { gmsh_api().model_mesh_generate(dim); }
void gmsh::model::mesh::getElementProperties(const int elementType, std::string& elementName, int& dim, int& order,
                                             int& numNodes, std::vector<double>& localNodeCoord, int& numPrimaryNodes) {
    gmsh_api().model_mesh_getElementProperties(elementType, elementName, dim, order, numNodes, localNodeCoord,
                                               numPrimaryNodes);
}
void gmsh::model::mesh::getElements(std::vector<int>& elementTypes, std::vector<std::vector<std::size_t> >& elementTags,
                                    std::vector<std::vector<std::size_t> >& nodeTags, const int dim, const int tag) {
    gmsh_api().model_mesh_getElements(elementTypes, elementTags, nodeTags, dim, tag);
}
void gmsh::model::mesh::getNodes(std::vector<std::size_t>& nodeTags, std::vector<double>& coord,
                                 std::vector<double>& parametricCoord, const int dim, const int tag,
                                 const bool includeBoundary, const bool returnParametricCoord) {
    gmsh_api().model_mesh_getNodes(nodeTags, coord, parametricCoord, dim, tag, includeBoundary, returnParametricCoord);
}
void gmsh::model::mesh::getNodesForPhysicalGroup(const int dim, const int tag, std::vector<std::size_t>& nodeTags,
                                                 std::vector<double>& coord) {
    gmsh_api().model_mesh_getNodesForPhysicalGroup(dim, tag, nodeTags, coord);
}
void gmsh::model::mesh::setOrder(const int order) { gmsh_api().model_mesh_setOrder(order); }
void gmsh::model::mesh::setTransfiniteAutomatic(const gmsh::vectorpair& dimTags, const double cornerAngle,
                                                const bool recombine) {
    gmsh_api().model_mesh_setTransfiniteAutomatic(dimTags, cornerAngle, recombine);
}
void gmsh::model::mesh::setTransfiniteCurve(const int tag, const int numNodes, const std::string& meshType,
                                            const double coef) {
    gmsh_api().model_mesh_setTransfiniteCurve(tag, numNodes, meshType, coef);
}
int gmsh::model::occ::addBox(const double x, const double y, const double z, const double dx, const double dy,
                             const double dz, const int tag) {
    return gmsh_api().model_occ_addBox(x, y, z, dx, dy, dz, tag);
}
int gmsh::model::occ::addCylinder(const double x, const double y, const double z, const double dx, const double dy,
                                  const double dz, const double r, const int tag, const double angle) {
    return gmsh_api().model_occ_addCylinder(x, y, z, dx, dy, dz, r, tag, angle);
}
int gmsh::model::occ::addDisk(const double xc, const double yc, const double zc, const double rx, const double ry,
                              const int tag) {
    return gmsh_api().model_occ_addDisk(xc, yc, zc, rx, ry, tag);
}
int gmsh::model::occ::addEllipse(const double x, const double y, const double z, const double r1, const double r2,
                                 const int tag, const double angle1, const double angle2) {
    return gmsh_api().model_occ_addEllipse(x, y, z, r1, r2, tag, angle1, angle2);
}
int gmsh::model::occ::addLine(const int startTag, const int endTag, const int tag) {
    return gmsh_api().model_occ_addLine(startTag, endTag, tag);
}
int gmsh::model::occ::addPoint(const double x, const double y, const double z, const double meshSize, const int tag) {
    return gmsh_api().model_occ_addPoint(x, y, z, meshSize, tag);
}
int gmsh::model::occ::addRectangle(const double x, const double y, const double z, const double dx, const double dy,
                                   const int tag, const double roundedRadius) {
    return gmsh_api().model_occ_addRectangle(x, y, z, dx, dy, tag, roundedRadius);
}
int gmsh::model::occ::addSphere(const double xc, const double yc, const double zc, const double radius, const int tag,
                                const double angle1, const double angle2, const double angle3) {
    return gmsh_api().model_occ_addSphere(xc, yc, zc, radius, tag, angle1, angle2, angle3);
}
void gmsh::model::occ::addThruSections(const std::vector<int>& wireTags, gmsh::vectorpair& outDimTags, const int tag,
                                       const bool makeSolid, const bool makeRuled, const int maxDegree) {
    gmsh_api().model_occ_addThruSections(wireTags, outDimTags, tag, makeSolid, makeRuled, maxDegree);
}
int gmsh::model::occ::addWire(const std::vector<int>& curveTags, const int tag, const bool checkClosed) {
    return gmsh_api().model_occ_addWire(curveTags, tag, checkClosed);
}
void gmsh::model::occ::cut(const gmsh::vectorpair& objectDimTags, const gmsh::vectorpair& toolDimTags,
                           gmsh::vectorpair& outDimTags, std::vector<gmsh::vectorpair>& outDimTagsMap, const int tag,
                           const bool removeObject, const bool removeTool) {
    gmsh_api().model_occ_cut(objectDimTags, toolDimTags, outDimTags, outDimTagsMap, tag, removeObject, removeTool);
}
void gmsh::model::occ::dilate(const gmsh::vectorpair& dimTags, const double x, const double y, const double z,
                              const double a, const double b, const double c) {
    gmsh_api().model_occ_dilate(dimTags, x, y, z, a, b, c);
}
void gmsh::model::occ::extrude(const gmsh::vectorpair& dimTags, const double dx, const double dy, const double dz,
                               gmsh::vectorpair& outDimTags, const std::vector<int>& numElements,
                               const std::vector<double>& heights, const bool recombine) {
    gmsh_api().model_occ_extrude(dimTags, dx, dy, dz, outDimTags, numElements, heights, recombine);
}
void gmsh::model::occ::fuse(const gmsh::vectorpair& objectDimTags, const gmsh::vectorpair& toolDimTags,
                            gmsh::vectorpair& outDimTags, std::vector<gmsh::vectorpair>& outDimTagsMap, const int tag,
                            const bool removeObject, const bool removeTool) {
    gmsh_api().model_occ_fuse(objectDimTags, toolDimTags, outDimTags, outDimTagsMap, tag, removeObject, removeTool);
}
void gmsh::model::occ::getCenterOfMass(const int dim, const int tag, double& x, double& y, double& z) {
    gmsh_api().model_occ_getCenterOfMass(dim, tag, x, y, z);
}
void gmsh::model::occ::getMass(const int dim, const int tag, double& mass) {
    gmsh_api().model_occ_getMass(dim, tag, mass);
}
void gmsh::model::occ::getMatrixOfInertia(const int dim, const int tag, std::vector<double>& mat) {
    gmsh_api().model_occ_getMatrixOfInertia(dim, tag, mat);
}
void gmsh::model::occ::intersect(const gmsh::vectorpair& objectDimTags, const gmsh::vectorpair& toolDimTags,
                                 gmsh::vectorpair& outDimTags, std::vector<gmsh::vectorpair>& outDimTagsMap,
                                 const int tag, const bool removeObject, const bool removeTool) {
    gmsh_api().model_occ_intersect(objectDimTags, toolDimTags, outDimTags, outDimTagsMap, tag, removeObject,
                                   removeTool);
}
void gmsh::model::occ::rotate(const gmsh::vectorpair& dimTags, const double x, const double y, const double z,
                              const double ax, const double ay, const double az, const double angle) {
    gmsh_api().model_occ_rotate(dimTags, x, y, z, ax, ay, az, angle);
}
void gmsh::model::occ::synchronize() { gmsh_api().model_occ_synchronize(); }
void gmsh::model::occ::translate(const gmsh::vectorpair& dimTags, const double dx, const double dy, const double dz) {
    gmsh_api().model_occ_translate(dimTags, dx, dy, dz);
}
void gmsh::model::setPhysicalName(const int dim, const int tag, const std::string& name) {
    gmsh_api().model_setPhysicalName(dim, tag, name);
}
void gmsh::option::setNumber(const std::string& name, const double value) { gmsh_api().option_setNumber(name, value); }
void gmsh::write(const std::string& fileName) { gmsh_api().write(fileName); }
