// Python bindings of the air's dispersion (media/dispersed_field.h).
#include "generated/docstrings.h"
#include "refracta/bindings/bind_media.h"
#include "refracta/media/dispersed_field.h"

#include <limits>

namespace refracta {

void bind_dispersion(py::module_& m) {
  py::class_<DispersedField, IndexField, std::shared_ptr<DispersedField>> cls(m, "DispersedField", DOC(refracta, DispersedField));
  auto make = [](std::shared_ptr<IndexField> base, double scale) {
    return std::make_shared<DispersedField>(base, scale);
  };
  cls.def(py::init(make), py::arg("base"), py::arg("scale"))
      .def_property_readonly("base", [](const DispersedField& f) { return unconst(f.base()); })
      .def_property_readonly("scale", &DispersedField::scale);
  // (base, scale, wavelength): the wavelength (NaN where not known) kept, so that a field dispersed
  // to 450 nm says so after a round trip; the earlier (base, scale) still read.
  cls.def(py::pickle(
      [](const DispersedField& f) { return py::make_tuple(unconst(f.base()), f.scale(), f.wavelength()); },
      [](const py::tuple& t) {
        if (t.size() != 2 && t.size() != 3) throw_invalid("DispersedField: bad pickle state (", t.size(), " items)");
        const double wavelength = t.size() == 3 ? t[2].cast<double>() : std::numeric_limits<double>::quiet_NaN();
        return std::make_shared<DispersedField>(t[0].cast<std::shared_ptr<IndexField>>(), t[1].cast<double>(), wavelength);
      }));

  m.def("air_dispersion_scale", &air_dispersion_scale, py::arg("wavelength"), py::arg("reference") = kDefaultFieldWavelength,
        "K(wavelength)/K(reference) of dry air (Birch & Downs 1993 Edlen formula at 101325 Pa, 288.15 K):\n"
        "the factor of n - 1 from the reference wavelength to `wavelength` [nm], both in [230, 2000].");
  m.def("field_reference_wavelength", &field_reference_wavelength, py::arg("field"),
        "The wavelength [nm] a field's n stands for: its `wavelength` parameter (PhysicalAtmosphere,\n"
        "TemperatureProfile, CurvedEarth over them), else 550.");
  m.def("dispersed_field",
        [](const std::shared_ptr<IndexField>& field, double wavelength, std::optional<double> reference) {
          return unconst(dispersed_field(field, wavelength, reference));
        },
        py::arg("field"), py::arg("wavelength"), py::arg("reference") = py::none(),
        "The field at `wavelength` [nm] (dry-air dispersion, n - 1 scaled by air_dispersion_scale from\n"
        "`reference`, default field_reference_wavelength(field)); CurvedEarth is rebuilt over its\n"
        "dispersed base; the field itself when nothing changes.");
}

}  // namespace refracta
