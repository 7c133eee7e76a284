#pragma once
/// \file ViewLayout.h
/// How the views of a document share the window: one view, two side by side, two stacked, or a
/// 2 × 2 grid. Plain data for session files; the viewer places the views (rows × columns).

#include <mvcl/core/Export.h>

#include <cstdint>
#include <string>

namespace mvcl {

enum class ViewLayout : uint8_t {
    Single,  ///< "1": the focused view fills the window
    Columns, ///< "1x2": one row of two views
    Rows,    ///< "2x1": two rows of one view
    Grid,    ///< "2x2"
};

/// The layout's cells: {rows, columns}.
struct ViewGrid {
    int rows = 1;
    int columns = 1;
    int cellCount() const { return rows * columns; }
};

MVCL_EXPORT ViewGrid viewGridOf(ViewLayout layout);
/// "1", "1x2", "2x1", "2x2".
MVCL_EXPORT const char *viewLayoutName(ViewLayout layout);
/// The layout named by viewLayoutName; throws mvcl::Error(`source`, problem) for another word.
MVCL_EXPORT ViewLayout parseViewLayout(const std::string &name, const std::string &source);

} // namespace mvcl
