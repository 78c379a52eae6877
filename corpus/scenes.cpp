// Placeholder translation unit so the corpus library exists before the scenes land.
namespace dcurve::corpus {}
