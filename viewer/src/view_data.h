#pragma once
// What `penumbra view` shows: the steps of its input (one file, or the passes of a .pvd
// series), the arrays of the data and their colour ranges over all steps (fixed, so that a
// series shows convergence rather than a rescaled picture), the scene camera, the exposure
// of the true-colour picture and the companion files of an output folder. The array list comes
// from the files, so a new array written by the pipeline needs no change here.

#include <vtkDataSet.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::viewer {

struct CameraPreset {
    double eye[3], look_at[3], up[3]; ///< metres
    double fov_deg = 45;
    bool fov_axis_x = true;
    int width = 0, height = 0; ///< the scene's image size, pixels
};

struct ArrayInfo {
    std::string name;
    bool point = false;    ///< shown from point data (smooth) rather than cell data
    bool has_cell = false; ///< a cell array of this name exists (picking reads the element)
    int components = 1;    ///< several: false colour shows the magnitude
    std::string unit;      ///< from the file's "units" field array, else from the name's suffix
    /// Over all steps, of the value (one component) or the magnitude (several).
    double min = 0, max = 0;
    double min_positive = 0; ///< 0 if no value is positive
};

struct ViewStep {
    double time = 0; ///< the .pvd timestep (shots of a progressive solve)
    std::string file;
};

class ViewData {
public:
    /// \brief Opens \p input (see ViewOptions::input) and reads every step once for the ranges.
    explicit ViewData(const std::string& input);

    const std::string& source() const { return source_; }
    const std::vector<ViewStep>& steps() const { return steps_; }
    bool is_series() const { return series_; }
    /// \brief Reads one step (not cached: a series may be large).
    vtkSmartPointer<vtkDataSet> load(std::size_t step) const;

    /// True colour first when the data has radiosity, then the file's arrays.
    const std::vector<ArrayInfo>& arrays() const { return arrays_; }
    /// \brief The array called \p name, or nullptr.
    const ArrayInfo* find(const std::string& name) const;
    /// \brief All array names, comma-separated, for error messages.
    std::string array_names() const;

    const std::optional<CameraPreset>& camera() const { return camera_; }
    /// Multiplier from radiance (W/(sr·m²)) to display value of the true-colour picture.
    double exposure() const { return exposure_; }
    const std::string& sensors_file() const { return sensors_file_; }
    const std::string& discontinuities_file() const { return discontinuities_file_; }

private:
    void open_folder_or_file(const std::string& input);
    void read_pvd(const std::string& path);
    void catalogue(vtkDataSet* last);
    void update_ranges(vtkDataSet* data);

    std::string source_;
    bool series_ = false;
    std::vector<ViewStep> steps_;
    std::vector<ArrayInfo> arrays_;
    std::optional<CameraPreset> camera_;
    double exposure_ = 1;
    std::string sensors_file_, discontinuities_file_;
};

/// \brief Reads any VTK XML data set (.vtu, .vtp, ...). Throws InputError for a file that
///        does not exist or is not a data set, ExternalError with VTK's message otherwise.
vtkSmartPointer<vtkDataSet> read_dataset(const std::string& path);

/// \brief The true-colour array ("true_colour", 3 × unsigned char sRGB) of \p data from its
///        radiosity array (point data if \p point, else cell data): radiance B/π × exposure.
void add_true_colour(vtkDataSet* data, bool point, double exposure);

} // namespace penumbra::viewer
