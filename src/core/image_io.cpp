#include "core/image_io.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/file_commit.h"

namespace tandem {
namespace fs = std::filesystem;

bool hasExtension(const std::string& path, const std::string& ext) {
  if (path.size() < ext.size()) return false;
  return std::equal(ext.rbegin(), ext.rend(), path.rbegin(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) ==
           std::tolower(static_cast<unsigned char>(b));
  });
}

namespace {

void checkEncodable(const std::string& path, const Buffer& img) {
  if (img.width <= 0 || img.height <= 0 || img.channels <= 0)
    throw InputError(path, "", "refusing to write an empty image");
}

// OpenEXR writes through a stream; this one collects the file in memory, so the bytes reach
// the disk through the one checked write path (FileCommit).
class MemoryStream : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (pos_ + size_t(n) > bytes.size()) bytes.resize(pos_ + size_t(n));
    std::memcpy(bytes.data() + pos_, c, size_t(n));
    pos_ += size_t(n);
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = size_t(pos); }
  std::vector<unsigned char> bytes;

 private:
  size_t pos_ = 0;
};

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  const auto* p = static_cast<const unsigned char*>(data);
  out->insert(out->end(), p, p + size);
}

}  // namespace

void writeTextFile(const std::string& path, const std::string& text) {
  FileCommit c;
  c.stage(path, text);
  c.commit();
}

std::vector<unsigned char> encodePng(const std::string& path, const Buffer& img) {
  checkEncodable(path, img);
  int c = std::min(img.channels, 4);
  std::vector<unsigned char> bytes(img.pixelCount() * c);
  for (size_t i = 0; i < img.pixelCount(); ++i)
    for (int k = 0; k < c; ++k) {
      float v = img.data[i * img.channels + k];
      v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
      bytes[i * c + k] = static_cast<unsigned char>(std::lround(v * 255.0f));
    }
  std::vector<unsigned char> file;
  if (!stbi_write_png_to_func(appendBytes, &file, img.width, img.height, c, bytes.data(),
                              img.width * c))
    throw InputError(path, "", "PNG encoding failed");
  return file;
}

namespace {

// Channel names of one layer: a layer's own letters by what its values mean (R G B A for colours
// and material terms, X Y Z W for vectors, Z for depth, Y for other scalars), prefixed with
// "layer." as pbrt-v4 and Mitsuba name them; the unnamed layer keeps the bare letters.
std::vector<std::string> exrChannelNames(const ExrLayer& l) {
  static const char* kRgba[] = {"R", "G", "B", "A"};
  static const char* kXyzw[] = {"X", "Y", "Z", "W"};
  const Buffer& b = *l.buffer;
  const int c = b.channels;
  const bool vector = b.kind == BufferKind::Normal || b.kind == BufferKind::Position ||
                      b.kind == BufferKind::Motion;
  const bool named = l.channels.size() == size_t(c);
  std::vector<std::string> names;
  for (int k = 0; k < c; ++k) {
    std::string n = c > 4    ? (named ? l.channels[size_t(k)] : std::to_string(k))
                    : c == 1 ? (b.kind == BufferKind::Depth && !l.name.empty() ? "Z" : "Y")
                    : vector ? kXyzw[k]
                             : kRgba[k];
    names.push_back(l.name.empty() ? n : l.name + "." + n);
  }
  return names;
}

}  // namespace

std::vector<unsigned char> encodeExrLayers(const std::string& path,
                                           const std::vector<ExrLayer>& layers, bool half) {
  if (layers.empty()) throw InputError(path, "", "EXR encoding failed: no layers");
  for (const ExrLayer& l : layers) {
    checkEncodable(path, *l.buffer);
    if (l.buffer->width != layers[0].buffer->width || l.buffer->height != layers[0].buffer->height)
      throw InputError(path, l.name,
                       "layer is " + std::to_string(l.buffer->width) + "x" +
                           std::to_string(l.buffer->height) + ", not the image's " +
                           std::to_string(layers[0].buffer->width) + "x" +
                           std::to_string(layers[0].buffer->height));
  }
  const int w = layers[0].buffer->width, h = layers[0].buffer->height;
  MemoryStream stream;
  try {
    Imf::Header header(w, h);
    Imf::FrameBuffer fb;
    // OpenEXR converts on read but not on write: half channels need half pixels.
    std::vector<std::vector<Imath::half>> halves(layers.size());
    const size_t bytes = half ? sizeof(Imath::half) : sizeof(float);
    const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
    for (size_t li = 0; li < layers.size(); ++li) {
      const Buffer& img = *layers[li].buffer;
      if (half) {
        halves[li].resize(img.data.size());
        for (size_t i = 0; i < img.data.size(); ++i) halves[li][i] = Imath::half(img.data[i]);
      }
      const char* base = half ? (const char*)halves[li].data() : (const char*)img.data.data();
      const std::vector<std::string> names = exrChannelNames(layers[li]);
      for (size_t k = 0; k < names.size(); ++k) {
        if (header.channels().findChannel(names[k]))
          throw InputError(path, names[k], "two layers write the same channel");
        header.channels().insert(names[k], Imf::Channel(type));
        fb.insert(names[k], Imf::Slice(type, (char*)(base + k * bytes), bytes * img.channels,
                                       bytes * img.channels * img.width));
      }
    }
    // The file is complete (line-offset table included) once OutputFile is destroyed.
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("EXR encoding failed: ") + e.what());
  }
  return std::move(stream.bytes);
}

std::vector<unsigned char> encodeExr(const std::string& path, const Buffer& img, bool half) {
  return encodeExrLayers(path, {{"", &img}}, half);
}

void writePng(const std::string& path, const Buffer& img) {
  writeFileAtomically(path, encodePng(path, img));
}

void writeExr(const std::string& path, const Buffer& img, bool half) {
  writeFileAtomically(path, encodeExr(path, img, half));
}

namespace {

Buffer loadExr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    Imath::Box2i dw = file.header().dataWindow();
    int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    if (w <= 0 || h <= 0 || size_t(w) * h > (size_t(1) << 28))
      throw InputError(path, "dataWindow", "absurd image size");
    Buffer img(w, h, 3);
    const Imf::ChannelList& ch = file.header().channels();
    bool gray = ch.findChannel("Y") && !ch.findChannel("R");
    Imf::FrameBuffer fb;
    char* base = (char*)(img.data.data()) - (size_t(dw.min.y) * w + dw.min.x) * 3 * sizeof(float);
    const char* names[3] = {"R", "G", "B"};
    for (int k = 0; k < 3; ++k)
      fb.insert(gray ? "Y" : names[k],
                Imf::Slice(Imf::FLOAT, base + k * sizeof(float), 3 * sizeof(float),
                           3 * sizeof(float) * w, 1, 1, 0.0));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read EXR: ") + e.what());
  }
}

Buffer load8bit(const std::string& path, int wantChannels) {
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(path.c_str(), &w, &h, &n, wantChannels);
  if (!px) {
    std::string why = fs::exists(path) ? stbi_failure_reason() : "file not found";
    throw InputError(path, "", "cannot read image: " + why);
  }
  Buffer img(w, h, wantChannels);
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = px[i] / 255.0f;
  stbi_image_free(px);
  return img;
}

}  // namespace

Buffer loadImage(const std::string& path) {
  if (!hasExtension(path, ".exr")) {
    Buffer b = load8bit(path, 3);
    b.kind = BufferKind::Display;  // 8-bit files hold display-encoded colour
    return b;
  }
  return loadExr(path);
}

Buffer loadTextureFile(const std::string& path) {
  return load8bit(path, 4);
}

}  // namespace tandem
