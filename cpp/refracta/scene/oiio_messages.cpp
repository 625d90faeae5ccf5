// OIIO's global attributes: "debug", "threads".
#include "refracta/scene/oiio_messages.h"

#include <OpenImageIO/imageio.h>

#include <cstdlib>

namespace refracta {

void silence_oiio_debug_output() {
  if (std::getenv("OPENIMAGEIO_DEBUG") == nullptr) OIIO::attribute("debug", 0);
}

void limit_oiio_threads(int n) {
  OIIO::attribute("threads", n);
  OIIO::attribute("exr_threads", n);  // OpenEXR's pool: 0 is its default too
}

}  // namespace refracta
