#include "light_field_binding.h"

#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/view_crop.h"
#include "numpy_arrays.h"

namespace lfsp::python {
namespace {

// Metadata crosses as JSON text: Python's json module and nlohmann agree on every JSON value.
py::object MetadataToPython(const Metadata& metadata) {
  return py::module_::import("json").attr("loads")(metadata.dump());
}

Metadata MetadataFromPython(py::handle object) {
  if (!py::isinstance<py::dict>(object)) throw Error("metadata: expected a dict");
  const std::string text = py::module_::import("json").attr("dumps")(object).cast<std::string>();
  return Metadata::parse(text);
}

py::object SamplesOf(py::object self) {
  LightField& lf = self.cast<Bundle&>().light_field;
  const LightFieldShape& s = lf.shape();
  return FloatArrayOver(lf.data(), {s.nv, s.nu, s.height, s.width, s.channels}, self);
}

py::object WeightsOf(py::object self) {
  LightField& lf = self.cast<Bundle&>().light_field;
  if (!lf.HasWeights()) return py::none();
  const LightFieldShape& s = lf.shape();
  return FloatArrayOver(lf.weights().data(), {s.nv, s.nu, s.height, s.width}, self);
}

py::object DisparityOf(py::object self) {
  std::optional<DisparityMap>& disparity = self.cast<Bundle&>().disparity;
  if (!disparity) return py::none();
  return FloatArrayOver(disparity->data(), {disparity->height(), disparity->width()}, self);
}

py::object LabelsOf(py::object self) {
  std::optional<Labels>& labels = self.cast<Bundle&>().labels;
  if (!labels) return py::none();
  const LightFieldShape& s = labels->shape();
  return LabelArrayOver(labels->data(), {s.nv, s.nu, s.height, s.width}, self);
}

void SetDisparity(Bundle& bundle, py::object value) {
  if (value.is_none()) {
    bundle.disparity.reset();
    return;
  }
  DisparityMap disparity = DisparityFromArray(value, "disparity");
  const LightFieldShape& s = bundle.light_field.shape();
  if (disparity.width() != s.width || disparity.height() != s.height)
    throw Error("disparity: " + std::to_string(disparity.height()) + " x " + std::to_string(disparity.width()) +
                " does not match the views' " + std::to_string(s.height) + " x " + std::to_string(s.width));
  bundle.disparity = std::move(disparity);
}

void SetLabels(Bundle& bundle, py::object value) {
  if (value.is_none()) {
    bundle.labels.reset();
    return;
  }
  Labels labels = LabelsFromArray(value, "labels");
  RequireLabelsMatch(labels, bundle.light_field.shape(), "labels");
  bundle.labels = std::move(labels);
}

std::shared_ptr<Bundle> MakeBundle(py::object samples, py::object weights, const std::string& transfer,
                                   py::object metadata, py::object disparity, py::object labels) {
  auto bundle = std::make_shared<Bundle>();
  bundle->light_field = LightFieldFromArrays(samples, weights);
  bundle->light_field.transfer = TransferFromString(transfer);
  if (!metadata.is_none()) bundle->light_field.metadata = MetadataFromPython(metadata);
  SetDisparity(*bundle, disparity);
  SetLabels(*bundle, labels);
  return bundle;
}

}  // namespace

py::object ToPython(Bundle bundle) { return py::cast(std::make_shared<Bundle>(std::move(bundle))); }

Bundle CentralViewsOf(const Bundle& bundle, int n) {
  Bundle central;
  const LightFieldShape& shape = bundle.light_field.shape();
  central.light_field = n == shape.nu && n == shape.nv ? bundle.light_field : CentralViews(bundle.light_field, n);
  central.disparity = bundle.disparity;  // of the centre view, which stays the centre
  if (bundle.labels)
    central.labels = bundle.labels->shape().nu == n && bundle.labels->shape().nv == n ? *bundle.labels
                                                                                      : CentralViews(*bundle.labels, n);
  return central;
}

const Bundle& ChosenViews(const Bundle& bundle, int views, Bundle& storage) {
  const ViewChoice choice = ChooseViews(bundle.light_field, views);
  const LightFieldShape& shape = bundle.light_field.shape();
  if (choice.n == shape.nu && choice.n == shape.nv) return bundle;
  storage = CentralViewsOf(bundle, choice.n);
  return storage;
}

void BindLightField(py::module_& module) {
  py::class_<Bundle, std::shared_ptr<Bundle>>(module, "LightField", R"doc(
A 4D light field: nv x nu views of H x W RGB pixels, with optional per-ray weights, and what a bundle carries beside
it (a centre-view disparity, per-ray labels).

LightField(samples, weights=None, transfer="srgb", metadata=None, disparity=None, labels=None)

samples: array (nv, nu, H, W, 3) of float (used as they are, nominally 0..1), uint8 (/ 255) or uint16 (/ 65535), in
any memory layout (C-contiguous or not). It is always copied, once, into the light field's own float32 memory;
weights (nv, nu, H, W) the same. disparity (H, W) and labels (nv, nu, H, W, integers, -1 = unlabelled) are copied
too. NaN or infinite samples raise lfsp.Error.

The arrays it gives back (samples, weights, disparity, labels, numpy.asarray(lf)) are views of its own memory, never
copies: writing to them changes the light field, and they keep it alive.)doc")
      .def(py::init(&MakeBundle), py::arg("samples"), py::arg("weights") = py::none(), py::arg("transfer") = "srgb",
           py::arg("metadata") = py::none(), py::arg("disparity") = py::none(), py::arg("labels") = py::none())
      .def_property_readonly("samples", &SamplesOf,
                             "float32 array (nv, nu, H, W, 3) over the light field's memory (no copy)")
      .def_property_readonly("weights", &WeightsOf,
                             "float32 array (nv, nu, H, W) of per-ray weights (vignetting, validity), or None")
      .def_property("disparity", &DisparityOf, &SetDisparity,
                    "Centre-view disparity (H, W) float32 in pixels per view step (HCI convention), or None; "
                    "setting copies")
      .def_property("labels", &LabelsOf, &SetLabels,
                    "Per-ray labels (nv, nu, H, W) int32 (-1 = unlabelled), or None; setting copies")
      .def_property(
          "transfer", [](const Bundle& b) { return ToString(b.light_field.transfer); },
          [](Bundle& b, const std::string& name) { b.light_field.transfer = TransferFromString(name); },
          "How samples relate to radiance: 'srgb' (display-encoded, as PNG views usually are) or 'linear' (a "
          "decoder's scene-linear output)")
      .def_property(
          "metadata", [](const Bundle& b) { return MetadataToPython(b.light_field.metadata); },
          [](Bundle& b, py::object value) { b.light_field.metadata = MetadataFromPython(value); },
          "Free-form metadata (a dict, a copy: assign to change it): parameters.cfg sections, the decoder's record, "
          "the disparity range (meta.disp_min / disp_max)")
      .def_property_readonly("shape",
                             [](const Bundle& b) {
                               const LightFieldShape& s = b.light_field.shape();
                               return py::make_tuple(s.nv, s.nu, s.height, s.width, s.channels);
                             })
      .def(
          "__array__",
          [](py::object self, py::object dtype, py::object copy) {
            py::object samples = SamplesOf(self);
            if (!dtype.is_none()) return samples.attr("astype")(dtype);  // a converted copy, as numpy asks
            return copy.is_none() || !copy.cast<bool>() ? samples : samples.attr("copy")();
          },
          py::arg("dtype") = py::none(), py::arg("copy") = py::none())
      .def("__repr__", [](const Bundle& b) {
        std::string text =
            "<lfsp.LightField " + ToString(b.light_field.shape()) + ", " + ToString(b.light_field.transfer);
        if (b.light_field.HasWeights()) text += ", weights";
        if (b.disparity) text += ", disparity";
        if (b.labels) text += ", labels";
        return text + ">";
      });
}

}  // namespace lfsp::python
