// OpenImageIO bridge. Everything C++ stays in this file: every entry point catches
// all exceptions, and OIIO's own error text goes into the messages.
#include "io/image_read.h"
#include "io/file_mode.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace {

// Rows read per call: bounds the scratch buffer to a band, not the whole image.
const int BAND_ROWS = 64;

struct free_deleter {
    void operator()(void *p) const { std::free(p); }
};

// OIIO messages may span lines; keep ours on one.
std::string one_line(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
        s.pop_back();
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s.empty() ? std::string("no details") : s;
}

// Opens path and checks what every reader needs: a flat 2D image within the size limit.
int open_checked(const char *path, std::unique_ptr<OIIO::ImageInput> &in, og_error *err,
                 int max_size = IMAGE_MAX_SIZE) {
    struct stat st;
    if (stat(path, &st) != 0)
        return og_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    if (S_ISDIR(st.st_mode)) return og_error_set(err, "%s: is a folder, not an image", path);
    // Unassociated: colour as stored, not multiplied by the alpha we ignore.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    in = OIIO::ImageInput::open(path, &config);
    if (!in)
        return og_error_set(err, "%s: not an image OpenImageIO can read (%s)", path,
                            one_line(OIIO::geterror()).c_str());
    const OIIO::ImageSpec &spec = in->spec();
    const int w = spec.width, h = spec.height;
    if (spec.deep) return og_error_set(err, "%s: deep images are not supported", path);
    if (spec.depth > 1) return og_error_set(err, "%s: volume images are not supported", path);
    if (w <= 0 || h <= 0 || spec.nchannels <= 0)
        return og_error_set(err, "%s: image has zero size (%d x %d, %d channels)", path, w, h,
                            spec.nchannels);
    if (w > max_size || h > max_size)
        return og_error_set(err, "%s: image is %d x %d, larger than the %d x %d limit", path, w, h,
                            max_size, max_size);
    if (spec.tile_width > 0 && spec.tile_height <= 0)
        return og_error_set(err, "%s: tiled image with tile height %d", path, spec.tile_height);
    return 0;
}

int read_impl(const char *path, float **pixels, int *width, int *height, og_error *err) {
    std::unique_ptr<OIIO::ImageInput> in;
    if (open_checked(path, in, err) != 0) return -1;
    const OIIO::ImageSpec spec = in->spec();
    const int w = spec.width, h = spec.height;
    const int nch = spec.nchannels >= 3 ? 3 : 1; // grey (+ alpha) or colour (+ alpha)

    int band = BAND_ROWS;
    if (spec.tile_width > 0) band = std::max(1, BAND_ROWS / spec.tile_height) * spec.tile_height;
    std::unique_ptr<float, free_deleter> out(
        static_cast<float *>(std::malloc(sizeof(float) * (size_t)w * (size_t)h)));
    if (!out) return og_error_set(err, "%s: out of memory for %d x %d pixels", path, w, h);
    std::vector<float> buf((size_t)band * (size_t)w * (size_t)nch);

    for (int y0 = 0; y0 < h; y0 += band) {
        const int y1 = std::min(h, y0 + band);
        bool ok = spec.tile_width > 0
                      ? in->read_tiles(0, 0, spec.x, spec.x + w, spec.y + y0, spec.y + y1, spec.z,
                                       spec.z + 1, 0, nch, OIIO::TypeFloat, buf.data())
                      : in->read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, nch,
                                           OIIO::TypeFloat, buf.data());
        if (!ok)
            return og_error_set(err, "%s: cannot read pixels (%s)", path,
                                one_line(in->geterror()).c_str());
        for (int y = y0; y < y1; y++) {
            const float *src = buf.data() + (size_t)(y - y0) * w * nch;
            float *dst = out.get() + (size_t)y * w;
            for (int x = 0; x < w; x++) {
                const float *p = src + (size_t)x * nch;
                // Double keeps the weighted sum of huge finite values from overflowing.
                float v = nch == 1 ? p[0] : (float)(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
                if (!std::isfinite(v))
                    return og_error_set(err, "%s: pixel (%d, %d) is not finite", path, x, y);
                dst[x] = v;
            }
        }
    }
    in->close();
    *pixels = out.release();
    *width = w;
    *height = h;
    return 0;
}

// Removes the temp file unless the rename consumed it.
struct temp_file {
    std::string path;
    bool keep = false;
    ~temp_file() {
        if (!path.empty() && !keep) unlink(path.c_str());
    }
};

int fsync_path(const char *path, int flags) {
    int fd = open(path, O_RDONLY | flags);
    if (fd < 0) return -1;
    int rc = fsync(fd);
    close(fd);
    return rc;
}

// Writes one PNG atomically: temp file in the same folder, fsync, rename, then a
// best-effort fsync of the folder. The caller has checked the size.
int write_png_atomic(const char *path, const OIIO::ImageSpec &spec, const void *data,
                     og_error *err) {
    temp_file tmp;
    std::string name = std::string(path) + ".tmp-XXXXXX";
    int fd = mkstemp(&name[0]);
    if (fd < 0)
        return og_error_set(err, "%s: cannot create a temp file beside it: %s", path,
                            strerror(errno));
    tmp.path = name;
    fchmod(fd, og_new_file_mode()); // mkstemp's 0600 would carry over to the final file
    close(fd);

    // By format name: the temp file's name does not end in .png.
    auto out = OIIO::ImageOutput::create("png");
    if (!out)
        return og_error_set(err, "%s: OpenImageIO has no PNG writer (%s)", path,
                            one_line(OIIO::geterror()).c_str());
    if (!out->open(name, spec) || !out->write_image(spec.format, data) || !out->close())
        return og_error_set(err, "%s: cannot write PNG (%s)", path,
                            one_line(out->geterror()).c_str());
    if (fsync_path(name.c_str(), 0) != 0)
        return og_error_set(err, "%s: cannot sync: %s", path, strerror(errno));
    if (rename(name.c_str(), path) != 0)
        return og_error_set(err, "%s: cannot rename the temp file into place: %s", path,
                            strerror(errno));
    tmp.keep = true;
    std::string dir(path);
    size_t slash = dir.rfind('/');
    dir = slash == std::string::npos ? "." : slash == 0 ? "/" : dir.substr(0, slash);
    fsync_path(dir.c_str(), O_DIRECTORY); // best effort: the file itself is already durable
    return 0;
}

int check_write_size(const char *path, int width, int height, og_error *err) {
    if (width <= 0 || height <= 0 || width > IMAGE_MAX_SIZE || height > IMAGE_MAX_SIZE)
        return og_error_set(err, "%s: cannot write a %d x %d image (1 to %d per side)", path, width,
                            height, IMAGE_MAX_SIZE);
    return 0;
}

int write_impl(const char *path, const float *pixels, int width, int height, og_error *err) {
    if (check_write_size(path, width, height, err) != 0) return -1;
    const size_t n = (size_t)width * (size_t)height;
    std::vector<uint16_t> q(n);
    for (size_t i = 0; i < n; i++) {
        float v = pixels[i];
        if (std::isnan(v))
            return og_error_set(err, "%s: pixel (%d, %d) is NaN", path, (int)(i % width),
                                (int)(i / width));
        v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
        q[i] = (uint16_t)(v * 65535.0f + 0.5f);
    }
    OIIO::ImageSpec spec(width, height, 1, OIIO::TypeUInt16);
    spec.attribute("png:compressionLevel", 9);
    return write_png_atomic(path, spec, q.data(), err);
}

// 8- or 16-bit PNG of 1 to 4 channels (grey, grey+alpha, RGB, RGBA), rows top-first.
int write_png_impl(const char *path, const void *data, int width, int height, int channels,
                   int bits, og_error *err) {
    if (check_write_size(path, width, height, err) != 0) return -1;
    if (channels < 1 || channels > 4)
        return og_error_set(err, "%s: cannot write %d channels (1 to 4)", path, channels);
    if (bits != 8 && bits != 16)
        return og_error_set(err, "%s: cannot write %d-bit PNG (8 or 16)", path, bits);
    OIIO::ImageSpec spec(width, height, channels, bits == 8 ? OIIO::TypeUInt8 : OIIO::TypeUInt16);
    if (channels == 4) spec.attribute("oiio:UnassociatedAlpha", 1); // weights, not coverage
    // Level 1 (Blender's default PNG compression, 15%, is about the same): screenshots,
    // diffs, layer images and a planet export's twelve face images are written often;
    // zlib at level 6 took two thirds of an export for 8% smaller files.
    spec.attribute("png:compressionLevel", 1);
    return write_png_atomic(path, spec, data, err);
}

int write_rgb8_impl(const char *path, const unsigned char *rgb, int width, int height,
                    og_error *err) {
    return write_png_impl(path, rgb, width, height, 3, 8, err);
}

// Reads the whole image as 8-bit RGB in one call: OIIO converts 16-bit and float to
// uint8 (clamped, rounded); grey is replicated here and alpha is never read.
int read_rgb8_impl(const char *path, unsigned char **rgb, int *width, int *height, og_error *err) {
    std::unique_ptr<OIIO::ImageInput> in;
    if (open_checked(path, in, err) != 0) return -1;
    const OIIO::ImageSpec spec = in->spec();
    const int w = spec.width, h = spec.height;
    const int nch = spec.nchannels >= 3 ? 3 : 1;
    const size_t n = (size_t)w * (size_t)h;
    std::unique_ptr<unsigned char, free_deleter> out(
        static_cast<unsigned char *>(std::malloc(3 * n)));
    if (!out) return og_error_set(err, "%s: out of memory for %d x %d pixels", path, w, h);
    // Grey is read into the last third of the buffer, then spread forward in place.
    unsigned char *dst = out.get() + (nch == 1 ? 2 * n : 0);
    bool ok = spec.tile_width > 0 ? in->read_tiles(0, 0, spec.x, spec.x + w, spec.y, spec.y + h,
                                                   spec.z, spec.z + 1, 0, nch, OIIO::TypeUInt8, dst)
                                  : in->read_scanlines(0, 0, spec.y, spec.y + h, spec.z, 0, nch,
                                                       OIIO::TypeUInt8, dst);
    if (!ok)
        return og_error_set(err, "%s: cannot read pixels (%s)", path,
                            one_line(in->geterror()).c_str());
    in->close();
    if (nch == 1) {
        unsigned char *p = out.get();
        for (size_t i = 0; i < n; i++) { // write index 3i <= read index 2n + i: never ahead
            const unsigned char v = dst[i];
            p[3 * i] = p[3 * i + 1] = p[3 * i + 2] = v;
        }
    }
    *rgb = out.release();
    *width = w;
    *height = h;
    return 0;
}

// One channel in its stored type, converted to float without normalising: 16-bit
// 40000 reads as 40000.0, so the caller maps heights from what the file holds.
int read_channel_impl(const char *path, const char *channel, int max_size, float **samples,
                      int *width, int *height, int *kind, int *bits, char *desc, size_t desc_len,
                      og_error *err) {
    std::unique_ptr<OIIO::ImageInput> in;
    if (open_checked(path, in, err, max_size) != 0) return -1;
    const OIIO::ImageSpec spec = in->spec();
    const int w = spec.width, h = spec.height;
    int ch = 0;
    if (channel && *channel) {
        ch = spec.channelindex(channel);
        if (ch < 0) {
            std::string names;
            for (const auto &n : spec.channelnames)
                names += (names.empty() ? "" : ", ") + n;
            return og_error_set(err, "%s: no channel named '%s' (it has %s)", path, channel,
                                names.c_str());
        }
    }
    OIIO::TypeDesc type = spec.channelformat(ch);
    switch (type.basetype) {
    case OIIO::TypeDesc::UINT8:
    case OIIO::TypeDesc::UINT16:
    case OIIO::TypeDesc::UINT32:
        *kind = 0;
        break;
    case OIIO::TypeDesc::INT8:
    case OIIO::TypeDesc::INT16:
    case OIIO::TypeDesc::INT32:
        *kind = 1;
        break;
    case OIIO::TypeDesc::HALF:
    case OIIO::TypeDesc::FLOAT:
    case OIIO::TypeDesc::DOUBLE:
        *kind = 2;
        break;
    default:
        return og_error_set(err, "%s: channel %d has sample type %s, which is not a height", path,
                            ch, type.c_str());
    }
    *bits = (int)type.size() * 8;
    const char *chname = ch < (int)spec.channelnames.size() ? spec.channelnames[ch].c_str() : "?";
    snprintf(desc, desc_len, "%s %s, channel %s of %d", in->format_name(), type.c_str(), chname,
             spec.nchannels);
    // Stored integers are read as 32-bit of the same signedness (OIIO widens them
    // without scaling only within a type: read native, convert here).
    const size_t elem = type.size();
    int band = BAND_ROWS;
    if (spec.tile_width > 0) band = std::max(1, BAND_ROWS / spec.tile_height) * spec.tile_height;
    std::unique_ptr<float, free_deleter> out(
        static_cast<float *>(std::malloc(sizeof(float) * (size_t)w * (size_t)h)));
    if (!out) return og_error_set(err, "%s: out of memory for %d x %d samples", path, w, h);
    std::vector<unsigned char> buf((size_t)band * (size_t)w * elem);
    for (int y0 = 0; y0 < h; y0 += band) {
        const int y1 = std::min(h, y0 + band);
        bool ok = spec.tile_width > 0
                      ? in->read_tiles(0, 0, spec.x, spec.x + w, spec.y + y0, spec.y + y1, spec.z,
                                       spec.z + 1, ch, ch + 1, type, buf.data())
                      : in->read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, ch, ch + 1, type,
                                           buf.data());
        if (!ok)
            return og_error_set(err, "%s: cannot read samples (%s)", path,
                                one_line(in->geterror()).c_str());
        const size_t n = (size_t)(y1 - y0) * w;
        float *dst = out.get() + (size_t)y0 * w;
        const unsigned char *src = buf.data();
        for (size_t i = 0; i < n; i++) {
            const unsigned char *p = src + i * elem;
            float v;
            switch (type.basetype) {
            case OIIO::TypeDesc::UINT8:
                v = *p;
                break;
            case OIIO::TypeDesc::INT8:
                v = (float)*(const int8_t *)p;
                break;
            case OIIO::TypeDesc::UINT16:
                v = *(const uint16_t *)(const void *)p;
                break;
            case OIIO::TypeDesc::INT16:
                v = *(const int16_t *)(const void *)p;
                break;
            case OIIO::TypeDesc::UINT32:
                v = (float)*(const uint32_t *)(const void *)p;
                break;
            case OIIO::TypeDesc::INT32:
                v = (float)*(const int32_t *)(const void *)p;
                break;
            case OIIO::TypeDesc::HALF: {
                float f;
                OIIO::convert_pixel_values(type, p, OIIO::TypeFloat, &f, 1);
                v = f;
                break;
            }
            case OIIO::TypeDesc::FLOAT:
                std::memcpy(&v, p, 4);
                break;
            default:
                v = (float)*(const double *)(const void *)p;
                break;
            }
            dst[i] = v; // NaN / Inf stay: the caller reports or fills them
        }
    }
    in->close();
    *samples = out.release();
    *width = w;
    *height = h;
    return 0;
}

// Writes one channel atomically (temp file beside it, fsync, rename). format: 0 =
// uint16 from values already in 0..65535, 1 = float32, 2 = half. The file type comes
// from the extension of path.
int write_samples_impl(const char *path, const float *samples, int width, int height, int format,
                       const char *channel, og_error *err) {
    if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
        return og_error_set(err, "%s: cannot write a %d x %d image (1 to 65536 per side)", path,
                            width, height);
    std::string p(path);
    size_t dot = p.rfind('.');
    std::string ext = dot == std::string::npos ? "" : p.substr(dot + 1);
    for (auto &c : ext)
        c = (char)std::tolower((unsigned char)c);
    const char *oiio_format = ext == "png"                      ? "png"
                              : ext == "exr"                    ? "openexr"
                              : (ext == "tif" || ext == "tiff") ? "tiff"
                                                                : nullptr;
    if (!oiio_format) return og_error_set(err, "%s: not a .png, .tif or .exr name", path);
    if (ext == "png" && format != 0)
        return og_error_set(err, "%s: PNG holds integers only (16-bit)", path);
    const size_t n = (size_t)width * (size_t)height;
    OIIO::TypeDesc type = format == 0   ? OIIO::TypeUInt16
                          : format == 1 ? OIIO::TypeFloat
                                        : OIIO::TypeHalf;
    std::vector<uint16_t> q;
    const void *data = samples;
    if (format == 0) {
        q.resize(n);
        for (size_t i = 0; i < n; i++) {
            float v = samples[i];
            if (!(v >= 0.0f && v <= 65535.0f))
                return og_error_set(err, "%s: sample (%d, %d) = %g is outside 0..65535", path,
                                    (int)(i % width), (int)(i / width), (double)v);
            q[i] = (uint16_t)(v + 0.5f);
        }
        data = q.data();
    }
    OIIO::ImageSpec spec(width, height, 1, type);
    // OIIO stamps TIFF and EXR with the wall clock unless DateTime is given; empty leaves
    // it out, so the same export makes the same bytes (shards, reruns, CI caches).
    spec.attribute("DateTime", "");
    if (channel && *channel) spec.channelnames[0] = channel;
    if (ext == "png") spec.attribute("png:compressionLevel", 6);
    if (ext == "exr") spec.attribute("compression", "zip");
    if (ext == "tif" || ext == "tiff") spec.attribute("compression", "zip");

    temp_file tmp;
    std::string name = p + ".tmp-XXXXXX";
    int fd = mkstemp(&name[0]);
    if (fd < 0)
        return og_error_set(err, "%s: cannot create a temp file beside it: %s", path,
                            strerror(errno));
    tmp.path = name;
    fchmod(fd, og_new_file_mode());
    close(fd);
    auto out = OIIO::ImageOutput::create(oiio_format);
    if (!out)
        return og_error_set(err, "%s: OpenImageIO has no %s writer (%s)", path, oiio_format,
                            one_line(OIIO::geterror()).c_str());
    // The temp file's type is by format name; images this large are written in one go
    // (OIIO converts nothing: the buffer is already in the file's type).
    if (!out->open(name, spec) || !out->write_image(type, data) || !out->close())
        return og_error_set(err, "%s: cannot write (%s)", path, one_line(out->geterror()).c_str());
    if (fsync_path(name.c_str(), 0) != 0)
        return og_error_set(err, "%s: cannot sync: %s", path, strerror(errno));
    if (rename(name.c_str(), path) != 0)
        return og_error_set(err, "%s: cannot rename the temp file into place: %s", path,
                            strerror(errno));
    tmp.keep = true;
    return 0;
}

} // namespace

// libpng (under OIIO) prints "libpng error: ..." straight to stderr before OIIO turns
// the same text into its own error. While a file is read, fd 2 goes to a memory file:
// on failure the text is already in our message and is dropped; on success (warnings)
// it is passed on under the file's name. Reads only: they are few and one at a time,
// while writes run in parallel and would queue on the lock.
class stderr_capture {
    static std::mutex lock_;
    std::lock_guard<std::mutex> hold_{lock_};
    int saved_ = -1, mem_ = -1;

  public:
    stderr_capture() {
        fflush(stderr);
        mem_ = memfd_create("orogen-stderr", MFD_CLOEXEC);
        saved_ = mem_ >= 0 ? dup(2) : -1;
        if (saved_ >= 0) dup2(mem_, 2);
    }
    // Restores stderr; what was written meanwhile.
    std::string finish() {
        std::string text;
        if (saved_ < 0) return text;
        fflush(stderr);
        dup2(saved_, 2);
        close(saved_);
        saved_ = -1;
        char buf[4096];
        ssize_t n;
        for (off_t at = 0; (n = pread(mem_, buf, sizeof buf, at)) > 0; at += n)
            text.append(buf, (size_t)n);
        return text;
    }
    ~stderr_capture() {
        finish();
        if (mem_ >= 0) close(mem_);
    }
};
std::mutex stderr_capture::lock_;

// Runs an entry point's body: no C++ exception may cross into C.
template <typename Body>
static int guarded(const char *path, const char *verb, og_error *err, Body body) {
    try {
        if (strcmp(verb, "read") != 0) return body();
        stderr_capture capture;
        int rc = body();
        std::string said = capture.finish();
        if (rc == 0 && !said.empty())
            fprintf(stderr, "%s: %s", path,
                    said.back() == '\n' ? said.c_str() : (said + "\n").c_str());
        return rc;
    } catch (const std::exception &e) {
        return og_error_set(err, "%s: cannot %s image: %s", path, verb, e.what());
    } catch (...) {
        return og_error_set(err, "%s: cannot %s image: unknown error", path, verb);
    }
}

extern "C" __attribute__((visibility("default"))) int
orogen_image_module_read_luminance(const char *path, float **pixels, int *width, int *height,
                                   og_error *err) {
    *pixels = nullptr;
    *width = *height = 0;
    if (!path) return og_error_set(err, "image_read_luminance: no path");
    return guarded(path, "read", err, [&] { return read_impl(path, pixels, width, height, err); });
}

extern "C" __attribute__((visibility("default"))) int
orogen_image_module_write_gray16(const char *path, const float *pixels, int width, int height,
                                 og_error *err) {
    if (!path || !pixels) return og_error_set(err, "image_write_gray16: no path or pixels");
    return guarded(path, "write", err,
                   [&] { return write_impl(path, pixels, width, height, err); });
}

extern "C" __attribute__((visibility("default"))) int
orogen_image_module_read_rgb8(const char *path, unsigned char **rgb, int *width, int *height,
                              og_error *err) {
    *rgb = nullptr;
    *width = *height = 0;
    if (!path) return og_error_set(err, "image_read_rgb8: no path");
    return guarded(path, "read", err,
                   [&] { return read_rgb8_impl(path, rgb, width, height, err); });
}

extern "C" __attribute__((visibility("default"))) int
orogen_image_module_write_rgb8(const char *path, const unsigned char *rgb, int width, int height,
                               og_error *err) {
    if (!path || !rgb) return og_error_set(err, "image_write_rgb8: no path or pixels");
    return guarded(path, "write", err,
                   [&] { return write_rgb8_impl(path, rgb, width, height, err); });
}

extern "C" __attribute__((visibility("default"))) int
orogen_image_module_read_channel(const char *path, const char *channel, int max_size,
                                 float **samples, int *width, int *height, int *kind, int *bits,
                                 char *desc, size_t desc_len, og_error *err) {
    *samples = nullptr;
    *width = *height = 0;
    if (!path) return og_error_set(err, "image_read_channel: no path");
    return guarded(path, "read", err, [&] {
        return read_channel_impl(path, channel, max_size, samples, width, height, kind, bits, desc,
                                 desc_len, err);
    });
}

extern "C" __attribute__((visibility("default"))) int
orogen_image_module_write_samples(const char *path, const float *samples, int width, int height,
                                  int format, const char *channel, og_error *err) {
    if (!path || !samples) return og_error_set(err, "image_write_samples: no path or samples");
    return guarded(path, "write", err, [&] {
        return write_samples_impl(path, samples, width, height, format, channel, err);
    });
}

extern "C" __attribute__((visibility("default"))) int
orogen_image_module_write_png(const char *path, const void *data, int width, int height,
                              int channels, int bits, og_error *err) {
    if (!path || !data) return og_error_set(err, "image_write_png: no path or pixels");
    return guarded(path, "write", err,
                   [&] { return write_png_impl(path, data, width, height, channels, bits, err); });
}
