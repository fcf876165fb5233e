/* SPDX-License-Identifier: Apache-2.0 */
// image_oiio.cpp - the image module (librtcl_image.so, formats/image_module.h):
// encoding the formats of formats/image_formats.def that it writes (PNG,
// JPEG, TIFF, EXR, HDR, ...), and reading any format, over OpenImageIO 2.4.
//
// This is the project's only C++: it turns OIIO's C++ interface into plain C
// calls. It is a module of its own, loaded by the library on the first image
// of those formats (formats/image_load.c), so that programs that read and write no such
// image never map OpenImageIO. Every entry point catches every exception,
// because one escaping into C code would terminate the program. OIIO errors
// are always fetched (and so cleared) and put into the rt_error; nothing is
// printed. It calls nothing in the library: base/error.c is built into it.
#include "formats/image_module.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <unistd.h>

extern "C" {
#include "base/error.h"
#include "formats/image_check.h"
}

namespace {

// The rows of the one table of formats (formats/image_formats.def) that
// this module writes: the others are the library's own (PPM, PFM).
struct format_row {
    const char *extension;
    const char *name;
    int bits; // 8, 16: integer levels; 32: float
    bool module;
};
#define RT_CODER_MODULE true
#define RT_CODER_PNM    false
#define RT_CODER_PFM    false
const format_row format_rows[] = {
#define RT_IMAGE_FORMAT(ext, name, bits, coder, lossy) {ext, name, bits, RT_CODER_##coder},
#include "formats/image_formats.def"
#undef RT_IMAGE_FORMAT
};

// The module's row for path's extension (case-insensitive), or nullptr.
const format_row *format_of(const char *path) {
    const char *slash = std::strrchr(path, '/');
    const char *name = slash ? slash + 1 : path;
    const char *dot = std::strrchr(name, '.');
    if (!dot) return nullptr;
    std::string ext;
    for (const char *c = dot; *c; c++)
        ext += static_cast<char>(*c >= 'A' && *c <= 'Z' ? *c - 'A' + 'a' : *c);
    for (const format_row &row : format_rows)
        if (row.module && ext == row.extension) return &row;
    return nullptr;
}

// ".png, .jpg, ...": the extensions this module writes.
std::string supported_extensions() {
    std::string text;
    for (const format_row &row : format_rows)
        if (row.module) text += (text.empty() ? "" : ", ") + std::string(row.extension);
    return text;
}

// OIIO's messages can end in a newline; the rt_error message is one line.
std::string one_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    for (char &c : text)
        if (c == '\n') c = ' ';
    return text.empty() ? std::string("no further detail from OpenImageIO") : text;
}

// Clears OIIO's per-thread global error so that a later message is ours.
void clear_global_error() {
    (void)OIIO::geterror(true);
}

// Clamps to [0,1] and rounds to the nearest of 256 levels. NaN becomes 0 so
// that a bad pixel shows as black rather than as an arbitrary value.
unsigned char to_8bit(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return static_cast<unsigned char>(std::floor(static_cast<double>(v) * 255.0 + 0.5));
}

// The same for 65536 levels.
uint16_t to_16bit(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 65535;
    return static_cast<uint16_t>(std::floor(static_cast<double>(v) * 65535.0 + 0.5));
}

// Encodes through a temporary file, for the writers that cannot write to
// memory (OIIO's SGI and FITS): made in TMPDIR (or /tmp), opened by OIIO by
// its name and then at once unlinked, so that the file has a name only
// while OIIO opens it: a process interrupted or killed during the encoding
// leaves nothing in TMPDIR. OIIO writes through the stream it opened and
// the bytes are read back through the descriptor kept from mkstemps (the
// same file). The library still writes the target whole.
bool encode_via_file(const char *path, const OIIO::ImageSpec &spec, OIIO::TypeDesc type,
                     const void *pixels, std::vector<unsigned char> &encoded, std::string &error) {
    const char *dot = std::strrchr(path, '.');
    const char *dir = std::getenv("TMPDIR");
    std::string name = std::string(dir && *dir ? dir : "/tmp") + "/rtcl-image-XXXXXX" + dot;
    std::vector<char> templ(name.begin(), name.end());
    templ.push_back(0);
    int fd = mkstemps(templ.data(), static_cast<int>(std::strlen(dot)));
    if (fd < 0) {
        error = std::string("cannot create a temporary file in ") + (dir && *dir ? dir : "/tmp") +
                ": " + std::strerror(errno);
        return false;
    }
    bool ok = false;
    {
        auto out = OIIO::ImageOutput::create(templ.data());
        bool opened = out && out->open(templ.data(), spec);
        unlink(templ.data());
        if (!out)
            error = one_line(OIIO::geterror());
        else if (!opened)
            error = one_line(out->geterror());
        else {
            bool written = out->write_image(type, pixels);
            if (!written) error = one_line(out->geterror());
            bool closed = out->close();
            if (written && !closed) error = one_line(out->geterror());
            ok = written && closed;
        }
    }
    if (ok) {
        unsigned char chunk[65536];
        off_t at = 0;
        ssize_t got;
        while ((got = pread(fd, chunk, sizeof chunk, at)) > 0) {
            encoded.insert(encoded.end(), chunk, chunk + got);
            at += got;
        }
        ok = got == 0;
        if (!ok)
            error = std::string("cannot read the temporary file back: ") + std::strerror(errno);
    }
    close(fd);
    return ok;
}

// The time now as OIIO's "DateTime" wants it: "YYYY:MM:DD hh:mm:ss", local.
std::string time_stamp() {
    std::time_t now = std::time(nullptr);
    std::tm local;
    char text[32] = "";
    if (localtime_r(&now, &local)) std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
    return text;
}

// Clears the header fields through which OpenImageIO 2.4 puts more than the
// pixels into a file, so that equal pixels give equal files whatever the
// file's name and whatever was on the stack (tests/cli_outputs.sh):
//  - SGI: the 80-byte image name (offset 24) is left uninitialised, stack
//    bytes (pointers among them) when no ImageDescription is given, and the
//    module gives none; it is zeroed always, as the format's "no name";
//  - DPX: the 100-byte file name (offset 36) holds the target's file name,
//    so one frame written under two names gave two files; zeroed unless
//    metadata asks for it (the creation time there is asked for the same way).
// Both formats' magic numbers are checked first, so a writer of another
// layout is left alone.
void clear_varying_fields(const format_row *format, int metadata,
                          std::vector<unsigned char> &file) {
    const std::string name = format->name;
    if (name == "SGI" && file.size() >= 512 && file[0] == 0x01 && file[1] == 0xda)
        std::memset(file.data() + 24, 0, 80);
    const bool dpx_magic = file.size() >= 2048 && (std::memcmp(file.data(), "SDPX", 4) == 0 ||
                                                   std::memcmp(file.data(), "XPDS", 4) == 0);
    if (name == "DPX" && dpx_magic && !metadata) std::memset(file.data() + 36, 0, 100);
}

rt_status encode_image(const char *path, const rt_image *image, int metadata,
                       unsigned char **bytes_out, size_t *size_out, rt_error *err) {
    size_t count = 0;
    rt_status status = rt_image_check(image, "the", path, &count, err);
    if (status != RT_OK) return status;

    const format_row *format = format_of(path);
    if (!format)
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                            "unknown image file extension (supported: %s)",
                            supported_extensions().c_str());
    const OIIO::TypeDesc type = format->bits == 8    ? OIIO::TypeDesc::UINT8
                                : format->bits == 16 ? OIIO::TypeDesc::UINT16
                                                     : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(image->width, image->height, image->channels, type);
    // The colour channels are stored as given: an alpha channel is not
    // premultiplied into them.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (metadata) {
        spec.attribute("Software", "rtcl");
        spec.attribute("DateTime", time_stamp());
    } else {
        // OpenImageIO's EXR writer stamps capDate with the time unless the
        // spec has a DateTime; an integer one keeps it from doing so and is
        // dropped as the wrong type for capDate, so the file holds no time
        // (tests/cli_outputs.sh checks that two writes are the same bytes).
        // Its note about the drop is a debug message, printed unless OIIO's
        // debug output is off: the library never prints.
        OIIO::attribute("debug", 0);
        spec.attribute("DateTime", 0);
    }

    // The levels of an integer format, rounded here (NaN as 0), so that
    // every format rounds alike; floats are passed as they are.
    std::vector<unsigned char> bytes;
    std::vector<uint16_t> words;
    const void *pixels = image->pixels;
    if (format->bits == 8) {
        bytes.resize(count);
        for (size_t i = 0; i < count; i++) bytes[i] = to_8bit(image->pixels[i]);
        pixels = bytes.data();
    } else if (format->bits == 16) {
        words.resize(count);
        for (size_t i = 0; i < count; i++) words[i] = to_16bit(image->pixels[i]);
        pixels = words.data();
    }

    // OpenImageIO encodes into memory (its IOProxy); the library then writes
    // the file with every error checked (OIIO's PNG writer drops write
    // errors: a full disk gave a truncated file and success), whole or not
    // at all (base/atomic_file.h).
    clear_global_error();
    auto out = OIIO::ImageOutput::create(path);
    if (!out)
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                            "OpenImageIO has no writer for this file: %s",
                            one_line(OIIO::geterror()).c_str());
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    if (!out->supports("ioproxy")) {
        out.reset();
        std::string error;
        if (!encode_via_file(path, spec, type, pixels, encoded, error))
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot encode the image as %s: %s",
                                format->name, error.c_str());
    } else {
        if (!out->set_ioproxy(&memory))
            return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                                "OpenImageIO cannot write %s to memory", format->name);
        if (!out->open(path, spec))
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot encode the image as %s: %s",
                                format->name, one_line(out->geterror()).c_str());
        bool written = out->write_image(type, pixels);
        std::string write_error = written ? std::string() : one_line(out->geterror());
        bool closed = out->close();
        if (!written)
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot write pixels: %s",
                                write_error.c_str());
        if (!closed)
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot finish the file: %s",
                                one_line(out->geterror()).c_str());
    }
    clear_varying_fields(format, metadata, encoded);
    // malloc'ed: the library frees it with free().
    unsigned char *file = static_cast<unsigned char *>(std::malloc(encoded.size() + 1));
    if (!file)
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0,
                            "no memory for the %zu bytes of the encoded file", encoded.size());
    if (!encoded.empty()) std::memcpy(file, encoded.data(), encoded.size());
    *bytes_out = file;
    *size_out = encoded.size();
    return RT_OK;
}

// ---- a structural check of PNG files -------------------------------------
// libpng, as OIIO 2.4 drives it, prints "libpng error: ..." to stderr before
// OIIO reports the error (OIIO's handler returns, so libpng's default one
// runs too). The library must not print, so a PNG file is checked here
// first: signature, chunk lengths within the file, every chunk's CRC, a valid
// IHDR, PLTE where needed, IDAT and IEND. That catches cut-short and damaged
// files; only a file with correct CRCs around bad compressed data still
// reaches libpng's message.

const unsigned char png_signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};

struct crc_table {
    uint32_t entry[256];
    crc_table() {
        for (uint32_t n = 0; n < 256; n++) {
            uint32_t c = n;
            for (int k = 0; k < 8; k++) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            entry[n] = c;
        }
    }
};

// The CRC-32 of PNG (and zlib); start with 0xFFFFFFFF, invert at the end.
uint32_t crc32_update(uint32_t crc, const unsigned char *data, size_t size) {
    static const crc_table table; // built once, thread-safely
    for (size_t i = 0; i < size; i++) crc = table.entry[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
    return crc;
}

uint32_t big_endian_32(const unsigned char *b) {
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | (uint32_t)b[3];
}

bool png_ihdr_valid(const unsigned char *d) {
    uint32_t width = big_endian_32(d), height = big_endian_32(d + 4);
    int depth = d[8], color = d[9];
    if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu) return false;
    if (d[10] != 0 || d[11] != 0 || d[12] > 1) return false; // compression, filter, interlace
    switch (color) {
    case 0:
        return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3:
        return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:
    case 4:
    case 6:
        return depth == 8 || depth == 16;
    default:
        return false;
    }
}

// Empty when the PNG file's structure is sound, else the reason. Files that do
// not start with the PNG signature are left to OIIO.
std::string png_structure_problem(std::FILE *file) {
    unsigned char head[8];
    if (std::fread(head, 1, 8, file) != 8 || std::memcmp(head, png_signature, 8) != 0)
        return std::string();
    bool seen_ihdr = false, seen_plte = false, seen_idat = false, palette = false;
    std::unique_ptr<unsigned char[]> buffer(new unsigned char[1 << 16]);
    for (long chunk = 0;; chunk++) {
        unsigned char header[8];
        if (std::fread(header, 1, 8, file) != 8) return "PNG file ends before its IEND chunk";
        uint32_t length = big_endian_32(header);
        char type[5] = {0};
        std::memcpy(type, header + 4, 4);
        for (int i = 0; i < 4; i++)
            if (!((type[i] >= 'A' && type[i] <= 'Z') || (type[i] >= 'a' && type[i] <= 'z')))
                return "damaged PNG file: a chunk type is not four letters";
        if (length > 0x7FFFFFFFu)
            return std::string("damaged PNG file: chunk ") + type + " is too long";
        bool is_ihdr = std::strcmp(type, "IHDR") == 0;
        if (chunk == 0 && (!is_ihdr || length != 13))
            return "damaged PNG file: it does not begin with an IHDR chunk";
        uint32_t crc = crc32_update(0xFFFFFFFFu, header + 4, 4);
        unsigned char ihdr[13] = {0};
        for (uint32_t left = length; left > 0;) {
            size_t part = left < (1u << 16) ? left : (1u << 16);
            if (std::fread(buffer.get(), 1, part, file) != part)
                return std::string("PNG file ends inside its ") + type + " chunk";
            if (is_ihdr && length == 13) std::memcpy(ihdr, buffer.get(), 13);
            crc = crc32_update(crc, buffer.get(), part);
            left -= static_cast<uint32_t>(part);
        }
        unsigned char stored[4];
        if (std::fread(stored, 1, 4, file) != 4)
            return std::string("PNG file ends inside its ") + type + " chunk";
        if ((crc ^ 0xFFFFFFFFu) != big_endian_32(stored))
            return std::string("damaged PNG file: CRC error in its ") + type + " chunk";
        if (is_ihdr) {
            if (seen_ihdr) return "damaged PNG file: two IHDR chunks";
            if (!png_ihdr_valid(ihdr)) return "damaged PNG file: invalid IHDR chunk";
            seen_ihdr = true;
            palette = ihdr[9] == 3;
        } else if (std::strcmp(type, "PLTE") == 0) {
            seen_plte = true;
        } else if (std::strcmp(type, "IDAT") == 0) {
            if (palette && !seen_plte) return "damaged PNG file: palette image without PLTE";
            seen_idat = true;
        } else if (std::strcmp(type, "IEND") == 0) {
            if (!seen_idat) return "damaged PNG file: no IDAT chunk";
            return std::string();
        }
    }
}

// Integer levels k of an n-bit file become k / (2^n - 1) as a correctly
// rounded float division, so that an 8-bit value written from k / 255.0f
// reads back as exactly the same float. (OIIO's own conversion multiplies by
// the reciprocal, which can be one ulp off.)
template <typename T>
bool read_levels(OIIO::ImageInput &in, OIIO::TypeDesc type, size_t count, float *pixels) {
    std::unique_ptr<T[]> levels(new T[count]);
    if (!in.read_image(0, 0, 0, in.spec().nchannels, type, levels.get())) return false;
    const float top = static_cast<float>(std::numeric_limits<T>::max());
    for (size_t i = 0; i < count; i++) pixels[i] = static_cast<float>(levels[i]) / top;
    return true;
}

bool read_pixels(OIIO::ImageInput &in, size_t count, float *pixels) {
    const OIIO::ImageSpec &spec = in.spec();
    bool one_format = spec.channelformats.empty();
    if (one_format && spec.format == OIIO::TypeDesc::UINT8)
        return read_levels<unsigned char>(in, OIIO::TypeDesc::UINT8, count, pixels);
    if (one_format && spec.format == OIIO::TypeDesc::UINT16)
        return read_levels<unsigned short>(in, OIIO::TypeDesc::UINT16, count, pixels);
    return in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels);
}

rt_status read_image(const char *path, rt_image *out, rt_error *err) {
    // A file we cannot open at all is an i/o error with the system's reason;
    // a file OIIO cannot make sense of is a parse error with OIIO's reason.
    std::FILE *probe = std::fopen(path, "rb");
    if (!probe)
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot open: %s", std::strerror(errno));
    std::string png_problem = png_structure_problem(probe);
    std::fclose(probe);
    if (!png_problem.empty())
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "%s", png_problem.c_str());

    // Keep colours as stored in files with alpha (no premultiplication).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    clear_global_error();
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in)
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "not a readable image: %s",
                            one_line(OIIO::geterror()).c_str());

    const OIIO::ImageSpec &spec = in->spec();
    if (spec.deep || spec.depth != 1)
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                            "deep and volume images are not supported");
    size_t count = 0;
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
        !rt_image_value_count(spec.width, spec.height, spec.nchannels, &count))
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0,
                            "unusable image size %dx%d with %d channels", spec.width, spec.height,
                            spec.nchannels);
    // The header's size is checked before any pixel memory is taken: a
    // small file can claim an image of terabytes.
    if ((uint64_t)spec.width * (uint64_t)spec.height > RT_MAX_IMAGE_READ_PIXELS ||
        spec.nchannels > RT_MAX_IMAGE_READ_CHANNELS)
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                            "the image is %dx%d with %d channels, beyond the limit of %llu pixels "
                            "and %d channels",
                            spec.width, spec.height, spec.nchannels,
                            (unsigned long long)RT_MAX_IMAGE_READ_PIXELS,
                            RT_MAX_IMAGE_READ_CHANNELS);

    float *pixels = static_cast<float *>(std::malloc(count * sizeof(float)));
    if (!pixels)
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0,
                            "no memory for %dx%d pixels with %d channels", spec.width, spec.height,
                            spec.nchannels);
    // Some readers (TIFF) report a cut-short file as an error but still
    // return true, so the error state counts too.
    bool read = read_pixels(*in, count, pixels);
    if (!read || in->has_error()) {
        std::free(pixels);
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0,
                            "cannot read pixels (is the file cut short?): %s",
                            one_line(in->geterror()).c_str());
    }
    out->width = spec.width;
    out->height = spec.height;
    out->channels = spec.nchannels;
    out->pixels = pixels;
    in->close();
    return RT_OK;
}

// A C++ exception that reached the C boundary (OIIO throws little, but the
// standard library may).
rt_status exception_error(rt_error *err, const char *path, const char *what) {
    return rt_error_set(err, RT_ERROR_BACKEND, path, 0, 0, "unexpected C++ exception: %s", what);
}

// Runs f, turning a C++ exception into an error about path: none may cross
// the module's C interface.
template <class F> rt_status guarded(rt_error *err, const char *path, F f) {
    try {
        return f();
    } catch (const std::bad_alloc &) {
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    } catch (const std::exception &e) {
        return exception_error(err, path, e.what());
    } catch (...) {
        return exception_error(err, path, "unknown exception");
    }
}

} // namespace

namespace {

rt_status module_encode(const char *path, const rt_image *image, int metadata,
                        unsigned char **bytes, size_t *size, rt_error *err) {
    *bytes = nullptr;
    *size = 0;
    if (!path || !path[0])
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, nullptr, 0, 0, "no output file name");
    return guarded(err, path,
                   [&] { return encode_image(path, image, metadata, bytes, size, err); });
}

rt_status module_read(const char *path, rt_image *out, rt_error *err) {
    if (!out)
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0, "output image is NULL");
    std::memset(out, 0, sizeof *out);
    if (!path || !path[0])
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, nullptr, 0, 0, "no input file name");
    return guarded(err, path, [&] { return read_image(path, out, err); });
}

const rt_image_module the_module = {RT_IMAGE_MODULE_ABI, sizeof(rt_image),
                                    sizeof(rt_error),    "OpenImageIO " OIIO_VERSION_STRING,
                                    module_encode,       module_read};

} // namespace

// The module's one exported symbol (the build hides every other).
extern "C" __attribute__((visibility("default"))) const rt_image_module *rtcl_image_module(void) {
    return &the_module;
}
