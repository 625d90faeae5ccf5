// OpenImageIO's debug() messages ("OIIO DEBUG: ...") are printed to stderr whenever its "debug"
// attribute is on, which it is in builds without NDEBUG (Debian's). They are notes for OIIO's
// developers; OIIO's errors reach refracta through geterror() and become exceptions.
#pragma once

namespace refracta {

// Turns OIIO's debug printing off, unless the user asked for it with OPENIMAGEIO_DEBUG.
void silence_oiio_debug_output();

}  // namespace refracta
