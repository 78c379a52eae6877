"""dcurve.encode on a worker thread, so Blender's main thread can move the progress bar
while the encoder (which releases the GIL) runs: Blender's API may only be called from the
main thread, and the encoder calls its progress callback from its own threads."""

import threading


class BackgroundEncode:
    def __init__(self, dcurve, frames, faces, keywords):
        self.fraction = 0.0
        self.result = None
        self.error = None
        self._thread = threading.Thread(target=self._run, args=(dcurve, frames, faces, keywords), daemon=True)

    def _run(self, dcurve, frames, faces, keywords):
        try:
            self.result = dcurve.encode(frames, faces, progress=self._progress, **keywords)
        except Exception as e:  # handed to the main thread, which reports it
            self.error = e

    def _progress(self, fraction):
        self.fraction = fraction

    def run(self, on_progress):
        """Encodes; `on_progress(fraction)` on the calling thread a few times a second."""
        self._thread.start()
        while self._thread.is_alive():
            self._thread.join(0.1)
            on_progress(self.fraction)
        if self.error is not None:
            raise self.error
        return self.result
