#include <mvcl/controller/InputEvent.h>

namespace mvcl {

InputEvent InputEvent::pointerPress(const glm::vec2 &position, PointerButton button, KeyModifier modifiers) {
    InputEvent event;
    event.type = Type::PointerPress;
    event.position = position;
    event.button = button;
    event.modifiers = modifiers;
    return event;
}

InputEvent InputEvent::pointerMove(const glm::vec2 &position, KeyModifier modifiers) {
    InputEvent event;
    event.type = Type::PointerMove;
    event.position = position;
    event.modifiers = modifiers;
    return event;
}

InputEvent InputEvent::pointerRelease(const glm::vec2 &position, PointerButton button, KeyModifier modifiers) {
    InputEvent event = pointerPress(position, button, modifiers);
    event.type = Type::PointerRelease;
    return event;
}

InputEvent InputEvent::scrolled(const glm::vec2 &position, const glm::vec2 &steps, KeyModifier modifiers) {
    InputEvent event;
    event.type = Type::Scroll;
    event.position = position;
    event.scroll = steps;
    event.modifiers = modifiers;
    return event;
}

InputEvent InputEvent::keyPress(Key key, KeyModifier modifiers) {
    InputEvent event;
    event.type = Type::KeyPress;
    event.key = key;
    event.modifiers = modifiers;
    return event;
}

InputEvent InputEvent::fileDrop(const glm::vec2 &position, std::vector<std::string> paths) {
    InputEvent event;
    event.type = Type::FileDrop;
    event.position = position;
    event.paths = std::move(paths);
    return event;
}

InputEvent InputEvent::resized(const glm::ivec2 &framebufferSize, float contentScale) {
    InputEvent event;
    event.type = Type::Resize;
    event.framebufferSize = framebufferSize;
    event.contentScale = contentScale;
    return event;
}

} // namespace mvcl
