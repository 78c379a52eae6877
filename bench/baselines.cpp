// Placeholder translation unit so the bench library exists before the baselines land.
namespace dcurve::bench {}
