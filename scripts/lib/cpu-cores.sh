# Sourced by the GPU suites that time the cpu backend on a share of the host's CPUs.
# own_cores N: N CPUs on N different physical cores (the first CPU of each core, in core order), comma
# separated; nothing where the host has fewer cores. taskset -c 0-1 may be one core's two hyperthreads,
# which share its arithmetic units: two threads there are not two cores.
own_cores() {
  lscpu -p=CPU,CORE,SOCKET 2>/dev/null | grep -v '^#' | sort -s -t, -k3,3n -k2,2n | awk -F, -v n="$1" '
    !seen[$3 "," $2]++ { cpus = cpus (count ? "," : "") $1; if (++count == n) { print cpus; exit } }'
}
# cpu_topology: each CPU's physical core and socket, one line ("cpu:core/socket ...").
cpu_topology() {
  lscpu -p=CPU,CORE,SOCKET 2>/dev/null | grep -v '^#' | awk -F, '{ printf "%s:%s/%s ", $1, $2, $3 } END { print "" }'
}
