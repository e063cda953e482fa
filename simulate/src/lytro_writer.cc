#include "lfsp/simulate/lytro_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"

namespace lfsp::simulate {
namespace {

using nlohmann::json;

json Bayer4(double r, double gr, double gb, double b) { return {{"r", r}, {"gr", gr}, {"gb", gb}, {"b", b}}; }
json Levels(int value) { return Bayer4(value, value, value, value); }

json Mosaic(const CameraModel& camera) {
  // Lytro names the 2x2 tile "r,gr:gb,b" and says which of its pixels sits at the top-left of the sensor.
  const std::string& p = camera.bayer;
  const std::string upper_left = p[0] == 'r' ? "r" : p[0] == 'b' ? "b" : (p[1] == 'r' ? "gr" : "gb");
  return {{"tile", "r,gr:gb,b"}, {"upperLeftPixel", upper_left}};
}

json WhiteBalanceGain(const CameraModel& camera) {
  return Bayer4(1.0 / camera.response_r, 1.0, 1.0, 1.0 / camera.response_b);
}

// The real Illum white TXT's ccmRgbToSrgbArray (the captures' matrices are CameraModel::ccm).
const std::vector<double> kIllumWhiteCcm = {2.4827811717987061,   -1.1018080711364746,  -0.38097298145294189,
                                            -0.36761483550071716, 1.6667767763137817,   -0.29916191101074219,
                                            -0.18722048401832581, -0.73317205905914307, 1.9203925132751465};

json Mla(const CameraModel& camera) {
  return {
      {"config", "com.lytro.mla.3"},
      {"tiling", "hexUniformRowMajor"},
      {"lensPitch", camera.lens_pitch},
      {"rotation", camera.rotation},
      {"defectArray", json::array()},
      {"scaleFactor", {{"x", camera.scale_x}, {"y", camera.scale_y}}},
      {"sensorOffset", {{"x", camera.sensor_offset_x}, {"y", camera.sensor_offset_y}, {"z", camera.sensor_offset_z}}}};
}

json IllumMla(const CameraModel& camera) {
  json mla = Mla(camera);
  mla.erase("defectArray");  // the Illum LFR has no defectArray (its white-image TXT does)
  return mla;
}

// Exposure as the camera would report it: shutter time proportional to the exposure factor (the camera's real
// shutter time at the default factor 0.7), for captures and white images alike. So scene-linear radiance is
// (capture - black) / (white image - black) * (white duration / capture duration), exactly.
double ExposureDuration(const CameraModel& camera, const RawCapture& raw) {
  return camera.exposure_duration * raw.exposure / 0.7;
}

json Roi() { return json::array({{{"top", 0}, {"left", 0}, {"bottom", 1}, {"right", 1}}}); }

json IllumSettings() {
  return {{"exposure",
           {{"bracketCount", 3},
            {"compensation", 0},
            {"mode", "shutterPriority"},
            {"meter", {{"mode", "evaluative"}, {"roiMode", "af"}, {"roi", Roi()}}},
            {"bracketEnable", false},
            {"bracketStep", 1},
            {"bracketOffset", 0},
            {"aeLock", false}}},
          {"whiteBalance", {{"tint", 0}, {"mode", "auto"}, {"cct", 5100}}},
          {"shutter", {{"selfTimerEnable", false}, {"selfTimerDuration", 2}, {"driveMode", "single"}}},
          {"focus",
           {{"afActuationMode", "single"},
            {"mode", "auto"},
            {"ringLock", false},
            {"bracketCount", 3},
            {"bracketEnable", false},
            {"afDriveMode", "single"},
            {"bracketStep", 3},
            {"bracketOffset", 0},
            {"roi", Roi()},
            {"captureLambda", 0}}},
          {"zoom", {{"ringLock", false}}},
          {"flash",
           {{"mode", "off"},
            {"exposureCompensation", 0},
            {"zoomMode", "auto"},
            {"curtainTriggerSync", "front"},
            {"afAssistMode", "auto"}}},
          {"depth", {{"assist", "off"}, {"histogram", "off"}, {"overlay", "off"}}}};
}

std::string Sha1Of(const std::string& text) {
  return decode::Sha1Reference(
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace

decode::RawPacking PackingFor(const CameraModel& camera) {
  if (camera.bits == 12) return decode::RawPacking::kBits12BigEndian;
  if (camera.bits == 10) return decode::RawPacking::kBits10Illum;
  throw Error("camera '" + camera.name + "': " + std::to_string(camera.bits) + "-bit raw has no Lytro packing");
}

json IllumFrameMetadata(const CameraModel& camera, const RawCapture& raw) {
  const double duration = ExposureDuration(camera, raw);
  json image = {{"width", raw.width},
                {"height", raw.height},
                {"orientation", 1},
                {"modulationExposureBias", camera.modulation_exposure_bias},
                {"limitExposureBias", 0.0},
                {"pixelPacking", {{"bitsPerPixel", camera.bits}, {"endianness", "little"}}},
                {"pixelFormat", {{"white", Levels(camera.white)}, {"black", Levels(camera.black)}, {"rightShift", 0}}},
                {"iso", camera.iso},
                {"originOnSensor", {{"x", 0}, {"y", 0}}},
                {"mosaic", Mosaic(camera)},
                {"color", {{"whiteBalanceGain", WhiteBalanceGain(camera)}, {"ccm", camera.ccm}}}};
  json per_ccm = json::array();
  per_ccm.push_back(
      {{"ccm",
        {2.006272077560425, -0.5362802147865295, -0.46999192237854004, -0.6019303798675537, 1.836044430732727,
         -0.23411400616168976, -0.8173090815544128, -1.6435128450393677, 3.4608218669891357}},
       {"cct", 2850}});
  per_ccm.push_back(
      {{"ccm",
        {2.4793264865875244, -1.2747985124588013, -0.20452789962291718, -0.5189455151557922, 1.6118407249450684,
         -0.09289517253637314, -0.3602483570575714, -1.0115599632263184, 2.3718082904815674}},
       {"cct", 4150}});
  per_ccm.push_back(
      {{"ccm",
        {2.1902196407318115, -1.0231428146362305, -0.16707684099674225, -0.4134329855442047, 1.7654914855957031,
         -0.3520585000514984, -0.18222910165786743, -0.7082417607307434, 1.8904708623886108}},
       {"cct", 6500}});
  json devices = {
      {"clock", {{"zuluTime", "2026-01-01T00:00:00.000Z"}, {"isTimeValid", true}}},
      {"sensor",
       {{"pixelPitch", camera.pixel_pitch},
        {"normalizedResponses",
         json::array({{{"b", camera.response_b}, {"gb", 1}, {"cct", 5100}, {"gr", 1}, {"r", camera.response_r}}})},
        {"perCcm", per_ccm},
        {"pixelWidth", raw.width},
        {"pixelHeight", raw.height},
        {"bitsPerPixel", camera.bits},
        {"mosaic", Mosaic(camera)},
        {"baseIso", 80},
        {"analogGain", Levels(1)}}},
      {"shutter",
       {{"mechanism", "focalPlaneCurtain"},
        {"frameExposureDuration", duration},
        {"pixelExposureDuration", duration},
        {"maxSyncSpeed", 0.004}}},
      {"mla", IllumMla(camera)},
      {"lens",
       {{"fNumber", camera.f_number},
        {"exitPupilOffset", {{"z", raw.setting.exit_pupil}}},
        {"zoomStep", raw.setting.zoom_step},
        {"focusStep", raw.setting.focus_step},
        {"opticalCenterOffset", {{"x", 0.0}, {"y", 0.0}}},
        {"focalLength", camera.focal_length},
        {"infinityLambda", camera.infinity_lambda}}},
      {"battery", {{"make", "Lytro"}, {"chargeLevel", 90}, {"model", "B01-3760"}, {"cycleCount", 1}}},
      {"accelerometer", {{"samples", json::array({{{"x", 0.0}, {"y", 9.81}, {"time", 0}, {"z", 0.0}}})}}}};
  return {{"schema", "http://schema.lytro.com/lfp/lytro_illum_public/1.3.4/lytro_illum_public_schema.json"},
          {"generator", "lfsp simulate"},
          {"image", image},
          {"devices", devices},
          {"camera", {{"make", "Lytro, Inc."}, {"model", camera.model}, {"firmware", camera.firmware}}},
          {"settings", IllumSettings()},
          {"algorithms",
           {{"awb", {{"roi", "fullFrame"}, {"computed", {{"cct", 5100}, {"gain", WhiteBalanceGain(camera)}}}}},
            {"ae", {{"computed", {{"ev", 0.0}}}, {"roi", "followAf"}}},
            {"af", {{"computed", {{"focusStep", raw.setting.focus_step}}}, {"roi", "focusRoi"}}}}},
          {"picture", {{"totalFrames", 1}, {"frameIndex", 0}, {"dcfDirectory", "100PHOTO"}, {"dcfFile", "IMG_0001"}}}};
}

json F01FrameMetadata(const CameraModel& camera, const RawCapture& raw) {
  const double duration = ExposureDuration(camera, raw);
  const json mosaic = Mosaic(camera);
  json image = {
      {"width", raw.width},
      {"height", raw.height},
      {"orientation", 1},
      {"representation", "rawPacked"},
      {"rawDetails",
       {{"pixelFormat", {{"rightShift", 0}, {"black", Levels(camera.black)}, {"white", Levels(camera.white)}}},
        {"pixelPacking", {{"endianness", "big"}, {"bitsPerPixel", camera.bits}}},
        {"mosaic", mosaic}}},
      {"color",
       {{"ccmRgbToSrgbArray", camera.ccm},
        {"gamma", 0.41666001081466675},
        {"applied", json::object()},
        {"whiteBalanceGain", WhiteBalanceGain(camera)}}},
      {"modulationExposureBias", camera.modulation_exposure_bias},
      {"limitExposureBias", 0}};
  json devices = {
      {"clock", {{"zuluTime", "2026-01-01T00:00:00.000Z"}}},
      {"sensor",
       {{"bitsPerPixel", camera.bits},
        {"mosaic", mosaic},
        {"iso", camera.iso},
        {"analogGain", Bayer4(5.4375, 4, 4, 4.625)},
        {"pixelPitch", camera.pixel_pitch}}},
      {"lens",
       {{"infinityLambda", camera.infinity_lambda},
        {"focalLength", camera.focal_length},
        {"zoomStep", raw.setting.zoom_step},
        {"focusStep", raw.setting.focus_step},
        {"fNumber", camera.f_number},
        {"temperature", 28.675750732421875},
        {"temperatureAdc", 2776},
        {"zoomStepperOffset", 0},
        {"focusStepperOffset", 27},
        {"exitPupilOffset", {{"z", raw.setting.exit_pupil}}}}},
      {"ndfilter", {{"exposureBias", 0}}},
      {"shutter",
       {{"mechanism", "sensorOpenApertureClose"},
        {"frameExposureDuration", duration},
        {"pixelExposureDuration", duration}}},
      {"soc", {{"temperature", 30.941009521484375}, {"temperatureAdc", 3203}}},
      {"accelerometer", {{"sampleArray", json::array({{{"x", 0.0}, {"y", 1.0}, {"z", 0.0}, {"time", 0}}})}}},
      {"mla", Mla(camera)}};
  return {{"type", "lightField"},
          {"image", image},
          {"devices", devices},
          {"modes", {{"creative", "auto"}}},
          {"camera", {{"make", "Lytro, Inc."}, {"model", camera.model}, {"firmware", camera.firmware}}}};
}

json FrameMetadata(const CameraModel& camera, const RawCapture& raw) {
  return camera.model == "F01" ? F01FrameMetadata(camera, raw) : IllumFrameMetadata(camera, raw);
}

json PrivateMetadata(const CameraModel& camera) {
  if (camera.model == "F01")
    return {{"camera", {{"serialNumber", camera.serial}}},
            {"devices", {{"sensor", {{"sensorSerial", camera.sensor_serial}}}}}};
  return {{"schema", "http://schema.lytro.com/lfp/lytro_illum_private/1.1.1/lytro_illum_private_schema.json"},
          {"generator", "lfsp simulate"},
          {"camera", {{"serialNumber", camera.serial}}},
          {"devices", {{"sensor", {{"serialNumber", camera.sensor_serial}}}}}};
}

json WhiteImageMetadata(const CameraModel& camera, const RawCapture& white) {
  const bool f01 = camera.model == "F01";
  const double duration = ExposureDuration(camera, white);
  const json mosaic = Mosaic(camera);
  json metadata = {
      {"camera", {{"make", "Lytro, Inc."}, {"model", camera.white_model}, {"firmware", camera.firmware}}},
      {"type", "lightField"},
      {"image",
       {{"width", white.width},
        {"height", white.height},
        {"orientation", 1},
        {"color",
         {{"ccmRgbToSrgbArray", f01 ? json(camera.ccm) : json(kIllumWhiteCcm)},
          {"gamma", f01 ? 0.41666001081466675 : 0.4},
          {"applied", json::object()},
          {"whiteBalanceGain", Levels(1)}}},
        {"modulationExposureBias", 0},
        {"limitExposureBias", 0},
        {"representation", "rawPacked"},
        {"rawDetails",
         {{"pixelFormat", {{"rightShift", 0}, {"black", Levels(camera.black)}, {"white", Levels(camera.white)}}},
          {"pixelPacking", {{"endianness", f01 ? "big" : "little"}, {"bitsPerPixel", camera.bits}}},
          {"mosaic", mosaic}}}}},
      {"devices",
       {{"clock", {{"zuluTime", "2026-01-01T00_00_00"}}},
        {"sensor",
         {{"bitsPerPixel", camera.bits},
          {"mosaic", mosaic},
          {"pixelPitch", camera.pixel_pitch},
          {"iso", 100},
          {"analogGain", Levels(1)},
          {"normalizedResponses",
           json::array({{{"cct", 5100}, {"r", camera.response_r}, {"gr", 1}, {"gb", 1}, {"b", camera.response_b}}})}}},
        {"mla", Mla(camera)},
        {"lens",
         {{"exitPupilOffset", {{"z", white.setting.exit_pupil}}},
          {"opticalCenterOffset", {{"x", 0.0}, {"y", 0.0}}},
          {"focalLength", camera.focal_length},
          {"infinityLambda", camera.infinity_lambda},
          {"zoomStep", white.setting.zoom_step},
          {"focusStep", white.setting.focus_step},
          {"fNumber", camera.f_number},
          {"temperature", 31.1572265625},
          {"temperatureAdc", 2712},
          {"zoomStepperOffset", -1},
          {"focusStepperOffset", -3}}},
        {"ndfilter", {{"exposureBias", 0}}},
        {"shutter",
         {{"mechanism", "sensorOpenApertureClose"},
          {"frameExposureDuration", duration},
          {"pixelExposureDuration", duration}}},
        {"soc", {{"temperature", 36.065643310546875}, {"temperatureAdc", 3037}}},
        {"accelerometer", {{"sampleArray", json::array({{{"x", 0.0}, {"y", 1.0}, {"z", 0.0}, {"time", 0}}})}}}}},
      {"modes",
       {{"creative", "auto"},
        {"manualControls", "auto"},
        {"exposureDurationMode", "auto"},
        {"isoMode", "auto"},
        {"ndFilterMode", "auto"},
        {"exposureLock", "false"}}}};
  json frame = {
      {"frame",
       {{"privateMetadata",
         {{"camera", {{"serialNumber", camera.serial}}},
          {"devices", {{"sensor", {{"sensorSerial", camera.sensor_serial}}}}}}},
        {"metadata", metadata},
        {"imageRef", "unknown"}}},
      {"parameters", {{"vendorContent", {{"com.lytro.tags", {{"darkFrame", false}, {"modulationFrame", true}}}}}}}};
  return {{"master",
           {{"version", {{"major", 1}, {"minor", 0}, {"provisionalDate", "2014-Sep-06"}}},
            {"picture",
             {{"viewArray", json::array()},
              {"accelerationArray", json::array()},
              {"frameArray", json::array({frame})},
              {"derivationArray", json::array({Sha1Of("lfsp-calibration-" + camera.serial)})}}},
            {"thumbnailArray", json::array()}}},
          {"compressedFrame",
           {{"metadata",
             {{"ccmRgbToYuvArray",
               {0.30078125, 0.5859375, 0.11328125, -0.171875, -0.33203125, 0.51171875, 0.51171875, -0.4296875,
                -0.08203125}},
              {"ccmYuvToRgbArray", {1, 0, 1.37109375, 1, -0.33984375, -0.69921875, 1, 1.73046875, 0}},
              {"representation", "jpeg"},
              {"demodulated", false}}}}}};
}

decode::LfpContainer BuildCaptureContainer(const CameraModel& camera, const RawCapture& raw) {
  std::vector<std::uint8_t> packed = decode::PackRaw(PackingFor(camera), raw.pixels, "simulated raw capture");
  decode::LfpContainer container;
  if (camera.model == "F01") {
    // F01 camera files: the table of contents first, then metadata, private metadata and the raw image. The
    // references are SHA-1s of the payloads, so compute them before writing the TOC.
    decode::LfpContainer content;
    const std::string metadata_ref = content.AddJson(FrameMetadata(camera, raw));
    const std::string private_ref = content.AddJson(PrivateMetadata(camera));
    const std::string image_ref = content.AddBinary(std::move(packed));
    json toc = {
        {"picture",
         {{"frameArray",
           json::array(
               {{{"frame",
                  {{"metadataRef", metadata_ref}, {"privateMetadataRef", private_ref}, {"imageRef", image_ref}}},
                 {"parameters",
                  {{"vendorContent", {{"com.lytro.tags", {{"darkFrame", false}, {"modulationFrame", false}}}}}}}}})},
          {"viewArray", json::array()},
          {"accelerationArray", json::array()},
          {"derivationArray", json::array({Sha1Of("lfsp-calibration-" + camera.serial)})}}},
        {"thumbnailArray", json::array()},
        {"version", {{"major", 1}, {"minor", 0}, {"provisionalDate", "2011-08-03"}}}};
    container.AddJson(toc, decode::SectionKind::kMetadata);
    for (auto& section : content.sections) container.sections.push_back(std::move(section));
    return container;
  }
  // Illum camera LFR: content sections first, the table of contents (frames[]) last.
  const std::string metadata_ref = container.AddJson(FrameMetadata(camera, raw));
  const std::string private_ref = container.AddJson(PrivateMetadata(camera));
  const std::string image_ref = container.AddBinary(std::move(packed));
  json toc = {
      {"schema", "http://schema.lytro.com/lfp/picture/2.1.4/picture_schema.json"},
      {"generators", json::array({"lfsp simulate"})},
      {"thumbnails", json::array()},
      {"derivations", json::array()},
      {"frames",
       json::array(
           {{{"frame",
              {{"metadataRef", metadata_ref}, {"privateMetadataRef", private_ref}, {"imageRef", image_ref}}}}})},
      {"annotations", json::array()},
      {"views", json::array()}};
  container.AddJson(toc, decode::SectionKind::kMetadata);
  return container;
}

std::string CaptureFileName(const CameraModel& camera) { return camera.model == "F01" ? "capture.lfp" : "capture.LFR"; }

void WriteMosaicJpeg(const CameraModel& camera, const RawCapture& raw, const std::filesystem::path& path, int quality) {
  if (quality < 1 || quality > 100) throw Error("mosaic JPEG quality " + std::to_string(quality) + " outside 1..100");
  cv::Mat mosaic(raw.height, raw.width, CV_8UC1);
  const double scale = 255.0 / camera.white;
  for (int y = 0; y < raw.height; ++y) {
    std::uint8_t* row = mosaic.ptr<std::uint8_t>(y);
    const std::uint16_t* codes = raw.pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(raw.width);
    for (int x = 0; x < raw.width; ++x)
      row[x] = static_cast<std::uint8_t>(std::min(255L, std::lround(codes[x] * scale)));
  }
  WriteImage(mosaic, path, 8, {{"Compression", "jpeg:" + std::to_string(quality)}});
  std::filesystem::path lossless = path;
  WriteImage(mosaic, lossless.replace_extension(".png"), 8);
}

void WriteWhiteImage(const CameraModel& camera, const RawCapture& white, const std::filesystem::path& raw_path) {
  const std::vector<std::uint8_t> packed = decode::PackRaw(PackingFor(camera), white.pixels, raw_path.string());
  decode::WriteFileBytesAtomic(packed, raw_path);
  std::filesystem::path txt = raw_path;
  txt.replace_extension(".TXT");
  const std::string text = WhiteImageMetadata(camera, white).dump(1, '\t');
  decode::WriteFileBytesAtomic(
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), txt);
}

json LensletGeometryJson(const CameraModel& camera, const RawCapture& raw) {
  const LensletLattice& l = raw.lattice;
  json centres = json::array();
  for (const auto& [i, j] : {std::pair{0, 0},
                             {1, 0},
                             {0, 1},
                             {l.columns - 1, 0},
                             {0, l.rows - 1},
                             {l.columns / 2, l.rows / 2},
                             {l.columns - 1, l.rows - 1}}) {
    const PixelPosition c = l.Centre(i, j);
    centres.push_back({{"i", i}, {"j", j}, {"x", c.x}, {"y", c.y}});
  }
  json hot = json::array();
  for (const auto& p : raw.hot_pixels) hot.push_back({p[0], p[1]});
  return {
      {"camera", camera.name},
      {"model", camera.model},
      {"sensor", {{"width", raw.width}, {"height", raw.height}, {"pixel_pitch_m", camera.pixel_pitch}}},
      {"bayer", camera.bayer},
      {"black", camera.black},
      {"white", camera.white},
      {"bits", camera.bits},
      {"response", {{"r", camera.response_r}, {"g", 1.0}, {"b", camera.response_b}}},
      {"exposure", raw.exposure},
      {"radiance",
       "scene-linear RGB = (capture - black) / (matching white image - black) * (white frameExposureDuration / "
       "capture frameExposureDuration), per Bayer pixel (responses and vignetting cancel); the decoded ground truth "
       "holds exactly this (before demosaicking), up to noise"},
      {"lens_setting",
       {{"zoomStep", raw.setting.zoom_step},
        {"focusStep", raw.setting.focus_step},
        {"exitPupil_m", raw.setting.exit_pupil}}},
      {"lattice",
       {{"formula",
         "centre(i,j) = origin + R(rotation) * ((i + shift(j)/2) * spacing, j * row_spacing), shift(j) = (j + "
         "row_shift) mod 2; pixel centres at integer coordinates, x right, y down; R(a) = [cos a, -sin a; sin a, cos "
         "a]"},
        {"spacing_px", l.spacing},
        {"row_spacing_px", l.RowSpacing()},
        {"scale_y", l.scale_y},
        {"rotation_rad", l.rotation},
        {"origin_px", {l.origin_x, l.origin_y}},
        {"row_shift", l.row_shift},
        {"columns", l.columns},
        {"rows", l.rows},
        {"disc_radius_px", camera.DiscRadius(raw.setting)},
        {"sample_centres", centres}}},
      {"lftoolbox_grid_model",
       {{"note", "1-based pixel coordinates as in LFToolbox; Rot = lattice rotation (rad, y down)"},
        {"HSpacing", l.spacing},
        {"VSpacing", l.RowSpacing()},
        {"HOffset", l.origin_x + 1.0},
        {"VOffset", l.origin_y + 1.0},
        {"Rot", l.rotation},
        {"Orientation", "horz"},
        {"FirstPosShiftRow", l.Shift(0) == 1 ? 1 : 2},
        {"UMax", l.columns},
        {"VMax", l.rows}}},
      {"decoded_grid",
       {{"views", raw.grid.views},
        {"view_step_px", raw.grid.view_step},
        {"width", raw.grid.width},
        {"height", raw.grid.height},
        {"mapping",
         "view (u,v), pixel (x,y) is the ray through the sensor point origin + R(rotation) * (x*sqrt(3)/2*spacing + "
         "(u-uc)*view_step, y*row_spacing + (v-vc)*view_step), uc = vc = (views-1)/2: x steps by sqrt(3)/2 lens "
         "pitches along a lens row (hex -> rect), y is the lens row"}}},
      {"hot_pixels", hot}};
}

}  // namespace lfsp::simulate
