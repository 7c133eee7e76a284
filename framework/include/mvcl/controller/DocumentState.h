#pragma once
/// \file DocumentState.h
/// The editable state of a document of several views as plain values — what one undo step of
/// the document restores and what a test compares: each view's SessionState and the links
/// between the views. The scene and the layout are not in it.

#include <mvcl/controller/SessionState.h>
#include <mvcl/io/ViewLink.h>

#include <vector>

namespace mvcl {

struct DocumentState {
    std::vector<SessionState> views;
    std::vector<ViewLink> links;

    bool operator==(const DocumentState &other) const = default;
};

} // namespace mvcl
