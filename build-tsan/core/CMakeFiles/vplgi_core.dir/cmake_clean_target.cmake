file(REMOVE_RECURSE
  "libvplgi_core.a"
)
