#include <mvcl/io/ViewLayout.h>

#include <mvcl/core/Error.h>

namespace mvcl {

ViewGrid viewGridOf(ViewLayout layout) {
    switch (layout) {
    case ViewLayout::Single: return {1, 1};
    case ViewLayout::Columns: return {1, 2};
    case ViewLayout::Rows: return {2, 1};
    case ViewLayout::Grid: return {2, 2};
    }
    return {1, 1};
}

const char *viewLayoutName(ViewLayout layout) {
    switch (layout) {
    case ViewLayout::Single: return "1";
    case ViewLayout::Columns: return "1x2";
    case ViewLayout::Rows: return "2x1";
    case ViewLayout::Grid: return "2x2";
    }
    return "1";
}

ViewLayout parseViewLayout(const std::string &name, const std::string &source) {
    for (ViewLayout layout : {ViewLayout::Single, ViewLayout::Columns, ViewLayout::Rows, ViewLayout::Grid})
        if (name == viewLayoutName(layout)) return layout;
    throw Error(source, "unknown layout '" + name + "' (known: 1, 1x2, 2x1, 2x2)");
}

} // namespace mvcl
