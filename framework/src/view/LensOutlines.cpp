#include <mvcl/view/LensOutlines.h>

#include <mvcl/lens/LensStack.h>
#include <mvcl/view/Framebuffer.h>

#include <algorithm>
#include <cmath>

namespace mvcl {

void drawLensOutlines(const LensStack &stack, Framebuffer &image) {
    const int width = image.width();
    const int height = image.height();
    for (const auto &lens : stack.lenses()) {
        const std::shared_ptr<const LensSnapshot> s = lens->snapshot();
        const LensRegion &region = s->region;
        if (!s->enabled || region.outlineWidth() <= 0.f) continue;
        const float halfWidth = 0.5f * region.outlineWidth();
        const PixelRect r = region.pixelBounds(width, height);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                const float d = std::abs(region.signedDistance({float(x) + 0.5f, float(y) + 0.5f}, width, height));
                // One pixel of linear falloff outside the stroke keeps the outline smooth.
                const float alpha = std::clamp(halfWidth + 0.5f - d, 0.f, 1.f);
                if (alpha > 0.f) image.at(x, y) = glm::mix(image.at(x, y), region.outlineColor(), alpha);
            }
    }
}

void drawLensOutlines(const LensStack &left, const LensStack &right, float dividerX, Framebuffer &image) {
    Framebuffer rightImage = image;
    drawLensOutlines(left, image);
    drawLensOutlines(right, rightImage);
    const int column = std::clamp(int(std::lround(dividerX * float(image.width()))), 0, image.width());
    for (int y = 0; y < image.height(); ++y) {
        for (int x = column; x < image.width(); ++x) image.at(x, y) = rightImage.at(x, y);
        if (column > 0) image.at(column - 1, y) = glm::vec3(1.f);
    }
}

} // namespace mvcl
