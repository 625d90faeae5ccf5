// OpenImageIO's debug() messages ("OIIO DEBUG: ...") are printed to stderr whenever its "debug"
// attribute is on, which it is in builds without NDEBUG (Debian's). They are notes for OIIO's
// developers; OIIO's errors reach refracta through geterror() and become exceptions.
#pragma once

namespace refracta {

// Turns OIIO's debug printing off, unless the user asked for it with OPENIMAGEIO_DEBUG.
void silence_oiio_debug_output();

// OIIO's own threads (image reads and writes, OpenEXR's pool, texture preparation) at most n,
// as set_threads limits refracta's; 0: OIIO's default, every core.
void limit_oiio_threads(int n);

}  // namespace refracta
