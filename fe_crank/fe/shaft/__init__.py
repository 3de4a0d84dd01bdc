"""The whole shaft on all its main bearings: pieces condensed onto their end faces, the
condensed shaft and its unit cases, the bearings' laws, the main-bearing loads and web
moments over the cycle (``whole_shaft`` is the entry point) and the fields on the whole
mesh."""
