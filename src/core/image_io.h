// Image files: PNG (8-bit sRGB, via stb) and EXR (32-bit float linear, via OpenEXR).
// Writes go through FileCommit (core/file_commit.h): complete and checked, or no file at all.
#pragma once
#include <string>
#include <vector>

#include "core/buffer.h"

namespace tandem {

// Writes 1-4 channel values already in [0,1] display space as an 8-bit PNG.
void writePng(const std::string& path, const Buffer& img);
// Writes a float EXR with channels R,G,B(,A) or Y for one channel; `half` stores 16-bit floats
// (relative error < 5e-4: small golden images).
void writeExr(const std::string& path, const Buffer& img, bool half = false);
// The files' bytes, for staging several files in one FileCommit (all or none). `path` only
// names the file in errors.
std::vector<unsigned char> encodePng(const std::string& path, const Buffer& img);
std::vector<unsigned char> encodeExr(const std::string& path, const Buffer& img, bool half = false);
// One layer of a multi-layer EXR: its channels are named "name.R", "name.G", ... (colours and
// material terms), "name.X", ... (normals, positions, motion), "name.Z" (depth) or "name.Y"
// (other scalars); an empty name gives the bare R, G, B (the image viewers show).
struct ExrLayer {
  std::string name;
  const Buffer* buffer = nullptr;
  // Up to four channels are named by the EXR conventions of their kind (R, G, B, A; X, Y, Z, W;
  // Y, or Z for depth); a wider buffer's by these (its slot's channelNamesOf), else by number.
  std::vector<std::string> channels = {};
};
// Every layer in one float (or half) EXR; all layers must have the same size.
std::vector<unsigned char> encodeExrLayers(const std::string& path,
                                           const std::vector<ExrLayer>& layers, bool half = false);
// Loads PNG/JPEG (values in [0,1], display encoded) or EXR (linear float); RGB output.
Buffer loadImage(const std::string& path);
// Loads an 8-bit image file for texturing: RGBA in [0,1], not yet linearised.
Buffer loadTextureFile(const std::string& path);

// Writes a text file (reports, CSV, JSON) through the same temporary-and-rename path.
void writeTextFile(const std::string& path, const std::string& text);

bool hasExtension(const std::string& path, const std::string& ext);  // case-insensitive

}  // namespace tandem
