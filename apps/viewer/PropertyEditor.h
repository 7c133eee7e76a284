#pragma once
// Controls generated from a lens's property declarations: one widget per declared type, with
// its range, unit and doc as tooltip. No lens has UI code of its own; plugins never call ImGui.

#include <mvcl/lens/PropertyDecl.h>
#include <mvcl/model/LayerTable.h>

namespace mvcl::viewer {

/// Draws the control of `decl` for `value`; returns true when the user changed it (the new
/// value is in `value`, already within the declared range).
bool editProperty(const PropertyDecl &decl, PropertyValue &value, const LayerTable &layers);

} // namespace mvcl::viewer
