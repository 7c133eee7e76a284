// Which properties form a gizmo, and the gizmo's shape read from and written back to them
// (Gizmo.h). The geometry and the drags are in Gizmo.cpp.

#include <mvcl/controller/Gizmo.h>

#include <mvcl/lens/PropertyValue.h>

#include <glm/geometric.hpp>

#include <algorithm>

namespace mvcl {

namespace {

bool endsWith(const std::string &name, std::string_view suffix) {
    return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A spatial property a gizmo can place: world or bounds space, or a space picked by a choice
// (which then offers at least one of them). View-space values follow the camera; a gizmo has no
// fixed place to show them.
bool isPlaceable(const PropertyDecl &decl) {
    const auto placeable = [](PropertySpace space) { return space != PropertySpace::View; };
    if (decl.spaceFrom.property.empty()) return placeable(decl.space);
    return std::ranges::any_of(decl.spaceFrom.spaces, [&](const auto &entry) { return placeable(entry.second); });
}

const PropertyDecl *findTyped(const PropertyTable &table, const std::string &name, PropertyType type) {
    const PropertyDecl *decl = findProperty(table, name);
    return decl && decl->type == type && (type == PropertyType::Real || isPlaceable(*decl)) ? decl : nullptr;
}

double largestSide(const LensContext &context) {
    if (context.sceneBounds.isEmpty()) return 1.0;
    const glm::vec3 e = context.sceneBounds.extent();
    return std::max(double(std::max(e.x, std::max(e.y, e.z))), 1e-30);
}

glm::dvec3 boundsCenter(const LensContext &context) {
    return context.sceneBounds.isEmpty() ? glm::dvec3(0.0) : glm::dvec3(context.sceneBounds.center());
}

glm::dvec3 unitOr(const glm::dvec3 &v, const glm::dvec3 &fallback) {
    const double length = glm::length(v);
    return length > 0.0 && std::isfinite(length) ? v / length : fallback;
}

std::string rotationText(const glm::dmat3 &axes) {
    glm::dmat4 m(1.0);
    for (int c = 0; c < 3; ++c) m[c] = glm::dvec4(axes[c], 0.0);
    return PropertyValue::transform(m).toString();
}

} // namespace

const std::string &GizmoDecl::primary() const {
    if (!position.empty()) return position;
    return kind == Kind::Arrow ? normal : rotation;
}

std::vector<GizmoDecl> gizmosOf(const PropertyTable &table) {
    std::vector<GizmoDecl> gizmos;
    std::vector<std::string> used;
    const auto take = [&](const std::string &name) { used.push_back(name); };
    const auto isUsed = [&](const std::string &name) { return std::ranges::find(used, name) != used.end(); };
    for (const PropertyDecl &decl : table) {
        if (isUsed(decl.name) || !isPlaceable(decl)) continue;
        GizmoDecl gizmo;
        if (decl.type == PropertyType::Box3) {
            gizmo.kind = GizmoDecl::Kind::Box;
            gizmo.position = decl.name;
            if (findTyped(table, decl.name + "Rotation", PropertyType::Transform)) gizmo.rotation = decl.name + "Rotation";
        } else if (decl.type == PropertyType::Point3) {
            gizmo.kind = GizmoDecl::Kind::Point;
            gizmo.position = decl.name;
            if (endsWith(decl.name, "Center")) {
                const std::string radius = decl.name.substr(0, decl.name.size() - 6) + "Radius";
                if (findTyped(table, radius, PropertyType::Real)) gizmo.kind = GizmoDecl::Kind::Sphere, gizmo.radius = radius;
            } else if (endsWith(decl.name, "Point")) {
                const std::string normal = decl.name.substr(0, decl.name.size() - 5) + "Normal";
                if (findTyped(table, normal, PropertyType::Vector3)) gizmo.kind = GizmoDecl::Kind::Plane, gizmo.normal = normal;
            }
        } else if (decl.type == PropertyType::Vector3) {
            gizmo.kind = GizmoDecl::Kind::Arrow;
            gizmo.normal = decl.name;
        } else if (decl.type == PropertyType::Transform) {
            gizmo.kind = GizmoDecl::Kind::Rings;
            gizmo.rotation = decl.name;
        } else {
            continue;
        }
        for (const std::string *name : {&gizmo.position, &gizmo.rotation, &gizmo.radius, &gizmo.normal})
            if (!name->empty()) take(*name);
        gizmos.push_back(gizmo);
    }
    return gizmos;
}

GizmoShape GizmoShape::read(const GizmoDecl &decl, const PropertyValues &values, const LensContext &context) {
    GizmoShape shape;
    shape.decl = decl;
    shape.space = values.space(decl.primary());
    shape.normalSpace = decl.normal.empty() ? shape.space : values.space(decl.normal);
    shape.size = 0.2 * largestSide(context);
    shape.center = boundsCenter(context);
    const glm::dmat4 rotation = decl.rotation.empty() ? glm::dmat4(1.0) : values.transform(decl.rotation);
    switch (decl.kind) {
    case GizmoDecl::Kind::Box: {
        const LensContext::OrientedBox box = context.sceneOrientedBox(values.box3(decl.position), rotation, shape.space);
        shape.center = box.center;
        shape.halfExtent = box.halfExtent;
        shape.axes = box.axes;
        break;
    }
    case GizmoDecl::Kind::Rings: shape.axes = context.sceneOrientedBox({}, rotation, shape.space).axes; break;
    case GizmoDecl::Kind::Sphere:
        shape.radius = context.sceneLength(values.real(decl.radius), shape.space);
        [[fallthrough]];
    case GizmoDecl::Kind::Plane:
    case GizmoDecl::Kind::Point:
        shape.center = context.scenePointInDouble(values.point3(decl.position), shape.space);
        break;
    case GizmoDecl::Kind::Arrow: break;
    }
    if (!decl.normal.empty())
        shape.normal = unitOr(glm::dvec3(context.sceneNormal(values.vector3(decl.normal), shape.normalSpace)),
                              {0.0, 0.0, 1.0});
    return shape;
}

std::vector<std::pair<std::string, std::string>> GizmoShape::propertyTexts(const LensContext &context) const {
    std::vector<std::pair<std::string, std::string>> texts;
    switch (decl.kind) {
    case GizmoDecl::Kind::Box:
        texts.emplace_back(decl.position,
                           PropertyValue::box3(context.propertyBox(center - halfExtent, center + halfExtent, space)).toString());
        break;
    case GizmoDecl::Kind::Sphere:
        texts.emplace_back(decl.radius, PropertyValue::real(context.propertyLength(radius, space)).toString());
        [[fallthrough]];
    case GizmoDecl::Kind::Plane:
    case GizmoDecl::Kind::Point:
        texts.emplace_back(decl.position, PropertyValue::point3(context.propertyPoint(center, space)).toString());
        break;
    case GizmoDecl::Kind::Arrow:
    case GizmoDecl::Kind::Rings: break;
    }
    if (!decl.rotation.empty()) texts.emplace_back(decl.rotation, rotationText(axes));
    if (!decl.normal.empty())
        texts.emplace_back(decl.normal, PropertyValue::vector3(unitOr(context.propertyVector(normal, normalSpace), normal))
                                            .toString());
    return texts;
}

std::string GizmoHandle::name() const {
    static const char *const kAxes[] = {"x", "y", "z"};
    switch (kind) {
    case Kind::Center: return "center";
    case Kind::Face: return std::string(side > 0 ? "+" : "-") + kAxes[axis];
    case Kind::Ring: return std::string("rotate-") + kAxes[axis];
    case Kind::Radius: return "radius";
    case Kind::Normal: return "normal";
    }
    return "center";
}

} // namespace mvcl
