#pragma once

namespace lfsp {

// The sRGB transfer curve (IEC 61966-2-1), the one copy every stage encodes and decodes with. Values are meant to
// lie in [0, 1]; callers clamp first where their data may not.

// Linear light -> sRGB-encoded value. The float overload computes in float (display and Lab previews, where speed
// matters and float is precise enough); the double one in double (tables built once).
float LinearToSrgb(float linear);
double LinearToSrgb(double linear);

// sRGB-encoded value -> linear light, in double. There is deliberately no float overload: callers pass floats and
// rely on the double curve, which a float overload would silently replace.
double SrgbToLinear(double encoded);

// The same curve through a 4096-segment table with linear interpolation (within 1e-5 of the exact curve), for
// per-sample use over whole light fields. Values outside [0, 1] are clamped first.
float SrgbToLinearTabulated(float encoded);

}  // namespace lfsp
