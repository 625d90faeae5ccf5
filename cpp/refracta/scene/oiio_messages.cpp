// OIIO's global "debug" attribute.
#include "refracta/scene/oiio_messages.h"

#include <OpenImageIO/imageio.h>

#include <cstdlib>

namespace refracta {

void silence_oiio_debug_output() {
  if (std::getenv("OPENIMAGEIO_DEBUG") == nullptr) OIIO::attribute("debug", 0);
}

}  // namespace refracta
