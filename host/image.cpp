// image.cpp - placeholder until the OpenImageIO shim lands.
#include "image.h"

#include <cstdlib>
#include <cstring>

extern "C" {
#include "error.h"
}

rt_status rt_image_write(const char *path, const rt_image *, rt_error *err) {
    return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0, "image output is not built yet");
}

rt_status rt_image_read(const char *path, rt_image *out, rt_error *err) {
    std::memset(out, 0, sizeof *out);
    return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0, "image input is not built yet");
}

void rt_image_free(rt_image *image) {
    std::free(image->pixels);
    image->pixels = nullptr;
}

rt_status rt_image_compare(const rt_image *, const rt_image *, rt_image_diff *, rt_image *,
                           rt_error *err) {
    return rt_error_set(err, RT_ERROR_UNSUPPORTED, nullptr, 0, 0, "image comparison is not built yet");
}
