#pragma once
/// \file InputEvent.h
/// What a window system tells a view, as plain data: the viewer translates its GLFW (or any
/// other) callbacks into these, and tests write them by hand. Positions are in framebuffer
/// pixels of the view, (0, 0) at the top-left corner, x right, y down: the pixels the image is
/// rendered in, not the window system's screen coordinates (which differ on high-DPI displays).

#include <mvcl/core/Export.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mvcl {

enum class PointerButton : uint8_t { None, Left, Middle, Right };

/// Modifier keys held during an event; combine with |.
enum class KeyModifier : uint8_t {
    None = 0,
    Shift = 1 << 0,
    Control = 1 << 1,
    Alt = 1 << 2,
    Super = 1 << 3,
};

constexpr KeyModifier operator|(KeyModifier a, KeyModifier b) { return KeyModifier(uint8_t(a) | uint8_t(b)); }
constexpr bool hasModifier(KeyModifier set, KeyModifier modifier) {
    return (uint8_t(set) & uint8_t(modifier)) == uint8_t(modifier) && modifier != KeyModifier::None;
}

/// The keys a controller acts on; everything else arrives as Other. Letters are the key's
/// position in a US layout, as GLFW reports them.
enum class Key : uint8_t {
    Other,
    Digit1, Digit2, Digit3, Digit4, Digit5, Digit6,
    Keypad1, Keypad3, Keypad7,
    B, D, E, F, P, Y, Z,
    Home, PageUp, PageDown, Delete, Backspace, Escape,
};

struct MVCL_EXPORT InputEvent {
    enum class Type : uint8_t {
        PointerPress,
        PointerMove,
        PointerRelease,
        Scroll,   ///< `scroll`: wheel steps, y > 0 away from the user (zoom in)
        KeyPress, ///< also sent for auto-repeat
        FileDrop, ///< `paths` dropped at `position`
        Resize,   ///< `framebufferSize` and `contentScale` of the view
    };

    Type type = Type::PointerMove;
    glm::vec2 position{0.f};     ///< framebuffer pixels (pointer, scroll, drop)
    PointerButton button = PointerButton::None;
    KeyModifier modifiers = KeyModifier::None;
    glm::vec2 scroll{0.f};
    Key key = Key::Other;
    std::vector<std::string> paths;
    glm::ivec2 framebufferSize{0};
    /// Framebuffer pixels per screen unit (2 on a typical high-DPI display): handles and hit
    /// tolerances are this many times larger in pixels so that they stay the same on screen.
    float contentScale = 1.f;

    static InputEvent pointerPress(const glm::vec2 &position, PointerButton button,
                                   KeyModifier modifiers = KeyModifier::None);
    static InputEvent pointerMove(const glm::vec2 &position, KeyModifier modifiers = KeyModifier::None);
    static InputEvent pointerRelease(const glm::vec2 &position, PointerButton button,
                                     KeyModifier modifiers = KeyModifier::None);
    static InputEvent scrolled(const glm::vec2 &position, const glm::vec2 &steps,
                               KeyModifier modifiers = KeyModifier::None);
    static InputEvent keyPress(Key key, KeyModifier modifiers = KeyModifier::None);
    static InputEvent fileDrop(const glm::vec2 &position, std::vector<std::string> paths);
    static InputEvent resized(const glm::ivec2 &framebufferSize, float contentScale = 1.f);
};

} // namespace mvcl
