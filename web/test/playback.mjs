// The timed loop of web/bench.mjs, imported by Node and by the page alike: median over
// `passes` of the milliseconds per frame of playing every frame in order through a freshly
// opened decoder (the open is not timed), as dcurve_web_native's `bench` does natively.
export async function playbackMs(loadDcurve, bytes, passes) {
  const dcurve = await loadDcurve();
  const ms = [];
  for (let p = 0; p < passes; ++p) {
    const dec = dcurve.open(bytes);
    const xyz = new Float32Array(dec.vertexCount * 3);
    const start = performance.now();
    for (let f = 0; f < dec.frameCount; ++f) dec.evaluateFrame(f, xyz);
    ms.push((performance.now() - start) / dec.frameCount);
    dec.close();
  }
  return ms.sort((a, b) => a - b)[ms.length >> 1];
}
