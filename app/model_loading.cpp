#include "model_loading.hpp"

#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"

namespace archet::cli {

Model load_validated_model(const std::string& path, const std::vector<std::string>& assignments,
                           double sample_rate) {
    Model model = load_model_file(path);
    for (const auto& a : assignments) apply_assignment(model, a);
    if (sample_rate > 0) model.sample_rate = sample_rate;
    validate_model(model);
    return model;
}

}  // namespace archet::cli
