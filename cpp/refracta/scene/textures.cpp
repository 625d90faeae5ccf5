// Textures: OIIO make_texture into the texture cache folder + TextureSystem.
#include "refracta/scene/textures.h"

#include "refracta/core/error.h"
#include "refracta/core/image.h"
#include "refracta/scene/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <mutex>
#include <vector>

namespace refracta {

namespace fs = std::filesystem;

struct Textures::Impl {
  OIIO::TextureSystem* system = nullptr;
  std::vector<OIIO::ustring> files;  // prepared (MIP-mapped, linear) files, by id
  std::vector<int> channels;          // their colour channels, by id: 1 (grey) or 3 (RGB)
  std::vector<bool> alpha;            // by id: the image has an alpha channel (after the colour, unless a mask)
  std::vector<int> opacity_channel;   // by id: the channel opacity() reads, -1 for none (opaque)
  std::mutex mutex;

  // Made with the first texture: a Scene without any keeps none (each private system's image cache
  // outlives it, ~25 kB: a trial counted 24.7 kB for every Scene).
  OIIO::TextureSystem* made() {
    if (!system) {
      system = OIIO::TextureSystem::create(false);  // private: our files, our options
      system->attribute("max_memory_MB", 512.0f);
    }
    return system;
  }
  // Its files closed and tiles dropped first: destroy() keeps a private system's image cache, and
  // with it an open handle to each texture read, until the process ran out of handles (a trial).
  // Not destroy(system, teardown_imagecache=true): OIIO 2.4 then frees the cache while threads'
  // per-thread records of it live on, and a later cache at the same address read them (an
  // assertion in resolve_udim, or a segfault, after a few hundred textured scenes).
  ~Impl() {
    if (!system) return;
    system->invalidate_all(/*force=*/true);
    system->close_all();
    OIIO::TextureSystem::destroy(system);
  }
};

Textures::Textures() : impl_(std::make_unique<Impl>()) {}
Textures::~Textures() = default;

namespace {

// Whether `folder` exists (made if missing) and this process may write there.
bool usable_folder(const fs::path& folder) {
  std::error_code error;
  fs::create_directories(folder, error);
  return fs::is_directory(folder, error) && ::access(folder.c_str(), W_OK | X_OK) == 0;
}

}  // namespace

std::string texture_cache_folder() {
  if (const char* chosen = std::getenv("REFRACTA_TEXTURE_CACHE"); chosen && *chosen) {
    if (!usable_folder(chosen)) {
      throw IoError(concat("REFRACTA_TEXTURE_CACHE='", chosen, "': the texture cache folder cannot be made or written"));
    }
    return chosen;
  }
  // The temporary folder ($TMPDIR); /tmp when TMPDIR names a folder that is missing or read-only
  // (temp_directory_path throws then).
  std::vector<fs::path> candidates;
  std::error_code error;
  const fs::path temp = fs::temp_directory_path(error);
  if (!error) candidates.push_back(temp / "refracta-textures");
  candidates.emplace_back("/tmp/refracta-textures");
  std::string tried;
  for (const fs::path& folder : candidates) {
    if (usable_folder(folder)) return folder.string();
    tried += concat(tried.empty() ? "'" : ", '", folder.string(), "'");
  }
  throw IoError(concat("no folder for the texture cache (tried ", tried, "): set REFRACTA_TEXTURE_CACHE to a writable folder"));
}

void check_texture_file(const std::string& path) {
  check_path_text(path);
  std::error_code error;
  if (!fs::exists(path, error)) throw MissingFile(concat("no such texture file: '", path, "'"));
  if (!fs::is_regular_file(path, error)) throw IoError(concat("cannot read texture '", path, "': not a regular file"));
}

namespace {

// A texture's colour channels: 1 for a grey image (with or without alpha), else 3.
int colour_channels(int channels) { return channels >= 3 ? 3 : 1; }

// The prepared copy of `path`: a tiled, MIP-mapped, half-float OpenEXR in the cache folder, named
// by the source's path, size and time, this preparation's version and its use, so an edited file
// is prepared again. A colour texture: its colour channels, linear, followed by its alpha when the
// image has one. A mask: one channel, its alpha or else its first channel, as stored. *channels:
// the colour channels (a mask's 1); *alpha: whether the image has alpha.
std::string prepare(const std::string& path, bool mask, int* channels, bool* alpha) {
  check_texture_file(path);
  std::error_code error;
  const auto size = fs::file_size(path, error);
  if (error) throw MissingFile(concat("no such texture file: '", path, "'"));
  const auto time = fs::last_write_time(path, error).time_since_epoch().count();
  constexpr int kPreparation = 5;  // 5: colour as stored, decoded, then the alpha as stored
  const size_t key = std::hash<std::string>()(
      concat(fs::absolute(path).string(), "|", size, "|", time, "|v", kPreparation, mask ? "|mask" : ""));
  const fs::path prepared = fs::path(texture_cache_folder()) / concat(std::hex, key, ".exr");

  check_png_complete(path);
  // Colours as stored, not premultiplied by their alpha (kept after them, as stored).
  OIIO::ImageSpec straight;
  straight.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageBuf source(path, 0, 0, nullptr, &straight);
  // The header first: a damaged or hostile one claiming a huge image (or display window, which
  // make_texture fills) was std::bad_alloc.
  if (!source.init_spec(path, 0, 0)) throw IoError(concat("cannot read texture '", path, "': ", source.geterror()));
  const OIIO::ImageSpec header = source.spec();
  *alpha = header.alpha_channel >= 0 && header.alpha_channel < header.nchannels;
  *channels = mask ? 1 : colour_channels(header.nchannels);
  if (fs::exists(prepared)) return prepared.string();
  if (header.full_width < 1 || header.full_height < 1 || header.width < 1 || header.height < 1) {
    throw IoError(concat("texture '", path, "': its header gives an empty image or display window"));
  }
  try {
    const std::string what = concat("texture '", path, "'");
    check_image_memory(header.width, header.height, 8.0 * header.nchannels, what.c_str());
    check_image_memory(header.full_width, header.full_height, 8.0 * header.nchannels, what.c_str());
  } catch (const std::invalid_argument& error) {
    throw IoError(error.what());
  }
  if (!source.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    throw IoError(concat("cannot read texture '", path, "': ", source.geterror()));
  }
  // A NaN or infinite texel would be filtered into its MIP levels and come back as NaN or as the
  // half-float limit -65504 in renders: refuse the file.
  const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(source);
  uint64_t non_finite = 0;
  for (size_t c = 0; c < stats.nancount.size(); ++c) non_finite += stats.nancount[c] + stats.infcount[c];
  if (non_finite > 0) {
    throw IoError(concat("texture '", path, "' has ", non_finite, " NaN or infinite texel values; textures must be finite"));
  }
  // 8- and 16-bit images store encoded colour (stored_gamma: sRGB unless the header names another
  // transfer): filter in linear light. The format as stored, from the header: read as float, the
  // buffer's own is float (and a PNG's 128 stayed 0.502).
  OIIO::ImageBuf linear;
  if (mask) {
    // A mask is data, not colour (MTL's map_d): its 128 of 255 is opacity 0.502, as Blender
    // reads masks -- decoded from sRGB as a colour it was 0.216.
    const int order[] = {*alpha ? header.alpha_channel : 0};
    const std::string name[] = {"Y"};
    linear = OIIO::ImageBufAlgo::channels(source, 1, order, {}, name);
  } else {
    const double gamma = stored_gamma(path);
    linear = *channels == header.nchannels ? source : OIIO::ImageBufAlgo::channels(source, *channels, {});
    if (gamma == 0.0) linear = OIIO::ImageBufAlgo::colorconvert(linear, "sRGB", "linear");
    if (gamma > 0.0 && gamma != 1.0) linear = OIIO::ImageBufAlgo::pow(linear, float(gamma));
    if (*alpha) {
      // The colour straight, not premultiplied, as pbrt-v4 and Mitsuba 3 read RGBA images: an
      // alpha that packs something else leaves the colour alone.
      const int order[] = {header.alpha_channel};
      linear = OIIO::ImageBufAlgo::channel_append(linear, OIIO::ImageBufAlgo::channels(source, 1, order));
    }
  }
  if (linear.has_error()) throw IoError(concat("texture '", path, "': ", linear.geterror()));
  // The source's ICC profile describes its encoded colours, not the linear copy; OpenEXR has no
  // place for it either (OIIO would print "Don't know what to do with ... ICCProfile").
  linear.specmod().erase_attribute("ICCProfile.*");
  OIIO::ImageSpec config;
  config.attribute("maketx:filtername", "lanczos3");
  config.attribute("tile_width", 64);
  config.attribute("tile_height", 64);
  config.attribute("compression", "zip");
  config.set_format(OIIO::TypeDesc::HALF);
  config.attribute("maketx:opaque_detect", 0);  // an alpha of 1 everywhere stays: lookups count the channels
  // Written under a name of this process and call, then renamed (atomic within the folder): a
  // session never reads a partial file, and sessions preparing the same texture at once each
  // write their own (the last rename wins; the copies are identical).
  static std::atomic<unsigned> calls{0};
  const fs::path partial = prepared.string() + concat(".", ::getpid(), "-", calls++, ".part.exr");
  if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, linear, partial.string(), config)) {
    fs::remove(partial, error);
    throw IoError(concat("cannot prepare texture '", path, "' in '", prepared.parent_path().string(), "': ", OIIO::geterror()));
  }
  fs::rename(partial, prepared, error);
  if (error) {
    fs::remove(partial, error);
    throw IoError(concat("cannot store the prepared texture for '", path, "' in '", prepared.parent_path().string(), "'"));
  }
  return prepared.string();
}

Vec3d to_rgb(const float* c, int channels) {
  return channels >= 3 ? Vec3d(c[0], c[1], c[2]) : Vec3d(c[0], c[0], c[0]);
}

}  // namespace

int Textures::add(const std::string& path, bool mask) {
  for (size_t i = 0; i < paths_.size(); ++i) {
    if (paths_[i] == path && masks_[i] == mask) return int(i);
  }
  int channels = 3;
  bool alpha = false;
  const std::string prepared = prepare(path, mask, &channels, &alpha);
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->made();
  impl_->files.emplace_back(prepared);
  impl_->channels.push_back(channels);
  impl_->alpha.push_back(alpha);
  // What opacity() reads: a mask's one channel, a colour texture's alpha after its colour.
  impl_->opacity_channel.push_back(mask ? 0 : alpha ? channels : -1);
  paths_.push_back(path);
  masks_.push_back(mask);
  return int(paths_.size() - 1);
}

Vec3d Textures::lookup(int id, const TextureLookup& at) const {
  OIIO::TextureOpt options;
  options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
  // Bilinear between texels (pbrt-v4's and Mitsuba 3's default): OIIO's default, smart bicubic, is
  // a B-spline on the finest level that spread a magnified checker's edge over ~3 texels (a
  // trial against Mitsuba 3: 20 px where Mitsuba's bilinear gives 10, at 10 px a texel).
  options.interpmode = OIIO::TextureOpt::InterpBilinear;
  float result[3] = {0, 0, 0};
  const OIIO::ustring& file = impl_->files.at(id);
  if (!impl_->system->texture(file, options, float(at.s), float(at.t), float(at.dsdx), float(at.dtdx),
                              float(at.dsdy), float(at.dtdy), 3, result)) {
    throw IoError(concat("texture lookup failed for '", paths_.at(id), "': ", impl_->system->geterror()));
  }
  return to_rgb(result, impl_->channels.at(id));
}

bool Textures::has_alpha(int id) const { return impl_->alpha.at(id); }

double Textures::opacity(int id, double s, double t) const {
  OIIO::TextureOpt options;
  options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
  options.interpmode = OIIO::TextureOpt::InterpBilinear;
  const int channel = impl_->opacity_channel.at(id);
  if (channel < 0) return 1.0;  // a colour texture without alpha is opaque
  options.firstchannel = channel;
  float result = 1.0f;
  if (!impl_->system->texture(impl_->files.at(id), options, float(s), float(t), 0.0f, 0.0f, 0.0f, 0.0f, 1, &result)) {
    throw IoError(concat("texture lookup failed for '", paths_.at(id), "': ", impl_->system->geterror()));
  }
  return std::clamp(double(result), 0.0, 1.0);
}

}  // namespace refracta
