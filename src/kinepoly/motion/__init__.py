"""Motion: the mechanism and its polygons over a sweep, frame by frame (``kinepoly animate``).

``frames`` turns a sweep into frame data (pure: the engine's arrays at fixed scales);
``gif`` draws them with matplotlib (GIF through pillow, MP4 through ffmpeg); ``html`` writes one
self-contained page with the frames as data and a small script; ``api`` is ``kinepoly.animate``
and ``kinepoly.draw``. Named ``motion`` so that the functions ``kinepoly.animate`` and
``kinepoly.draw`` do not shadow a subpackage.
"""
