! A rigid piston as the solid of a coupled run, in Fortran over libcosim_client: the physics of
! python/cosim/rigid_piston.py and examples/clients/c/rigid_piston.c (docs/clients.md).
!
!   rigid_piston SCENE --out DIR --coupler ENDPOINT [--token T] [--set key=value]... [--restart SET]
!
! The closed boundary of a rigid slab [left, right] x (the solid mesh's transverse box) moving along x. Newton's
! law under the interface pressures of the previous cycle, symplectic Euler; under coupling.mode robin the face
! pressure follows the fluid's impedance Z at the new velocity, taken implicitly. Mass and geometry from the
! scene's solid: box mesh with a rigid block named "piston". Writes DIR/piston.csv (t, x, v, F) at every output;
! at a checkpoint its state as the part solid.bin of the set (cosim_write_part: the C piston's layout), which
! --restart SET resumes from once the library checked it against the set's manifest (cosim_read_part).
module piston_geometry
  use, intrinsic :: iso_c_binding
  use cosim_client
  implicit none
  integer, parameter :: max_faces = 6
  ! The part: [1] layout version, [2] cycle, [3] time, [4] x, [5] v, [6] force, [7] v_sent, [8] bytes of
  ! piston.csv written, [9] face count n, then n face pressures and n impedances (doubles, exact).
  character(*), parameter :: part = "solid.bin"
  integer, parameter :: state_head = 9
  real(c_double), parameter :: state_version = 1

  type :: piston
    real(c_double) :: mass = 1, area = 1, left = -0.5_c_double, right = 0.5_c_double
    integer :: dim = 2
    real(c_double) :: lower(2) = 0, upper(2) = 1  ! transverse extent (y, z)
  end type

  type :: faces
    integer(c_int) :: count = 0, nodes_per_face = 0, vertex_count = 0
    real(c_double) :: centre(3 * max_faces), normal(3 * max_faces), area(max_faces), velocity(3 * max_faces)
    real(c_double) :: vertex(3 * 8)
    integer(c_int) :: face_vertex(4 * max_faces)  ! 0-based, as the C interface takes them
  end type

contains

  ! Mass, cross-section and extent from the scene's solid: section; p unchanged when the scene has none.
  subroutine piston_from_scene(c, p)
    type(c_ptr), intent(in) :: c
    type(piston), intent(inout) :: p
    real(c_double), allocatable :: lo(:), hi(:), rlo(:), rhi(:)
    real(c_double) :: density
    character(:), allocatable :: name
    character(64) :: key
    integer :: b, r, d, blocks, regions
    logical :: found
    type(piston) :: q
    if (cosim_scene_numbers(c, "solid.mesh.lower", lo) /= COSIM_OK) return
    if (cosim_scene_numbers(c, "solid.mesh.upper", hi) /= COSIM_OK) return
    if (size(lo) /= size(hi) .or. size(lo) < 1 .or. size(lo) > 3) return
    if (cosim_scene_length(c, "solid.blocks", blocks) /= COSIM_OK) return
    found = .false.
    do b = 0, blocks - 1
      write (key, '(a,i0,a)') "solid.blocks.", b, ".name"
      if (cosim_scene_string(c, key, name) /= COSIM_OK) cycle
      if (name /= "piston") cycle
      write (key, '(a,i0,a)') "solid.blocks.", b, ".density"
      found = cosim_scene_number(c, key, density) == COSIM_OK
      exit
    end do
    if (.not. found) return
    q%left = lo(1)
    q%right = hi(1)
    if (cosim_scene_length(c, "solid.mesh.regions", regions) /= COSIM_OK) regions = 0
    do r = 0, regions - 1
      write (key, '(a,i0,a)') "solid.mesh.regions.", r, ".block"
      if (cosim_scene_string(c, key, name) /= COSIM_OK) cycle
      if (name /= "piston") cycle
      write (key, '(a,i0,a)') "solid.mesh.regions.", r, ".lower"
      if (cosim_scene_numbers(c, key, rlo) /= COSIM_OK) return
      write (key, '(a,i0,a)') "solid.mesh.regions.", r, ".upper"
      if (cosim_scene_numbers(c, key, rhi) /= COSIM_OK) return
      q%left = max(lo(1), rlo(1))
      q%right = min(hi(1), rhi(1))
    end do
    q%dim = size(lo)
    q%area = 1
    do d = 2, q%dim
      q%area = q%area * (hi(d) - lo(d))
      q%lower(d - 1) = lo(d)
      q%upper(d - 1) = hi(d)
    end do
    q%mass = density * (q%right - q%left) * q%area
    p = q
  end subroutine

  ! The slab's boundary [x0, x1] x (lower, upper): outward normals, vertices, the rigid velocity (v, 0, 0).
  subroutine box_faces(p, x0, x1, v, f)
    type(piston), intent(in) :: p
    real(c_double), intent(in) :: x0, x1, v
    type(faces), intent(out) :: f
    integer, parameter :: faces2(2, 4) = reshape([3, 0, 1, 2, 0, 1, 2, 3], [2, 4])  ! -x, +x, -y, +y
    integer, parameter :: faces3(4, 6) = reshape([0, 4, 6, 2, 1, 3, 7, 5, 0, 1, 5, 4, 2, 6, 7, 3, 0, 2, 3, 1, &
                                                  4, 5, 7, 6], [4, 6])
    integer :: dim, i, k, d, j, ix, vtx
    real(c_double) :: xs(2), s, lo, hi, size_, x
    dim = p%dim
    xs = [x0, x1]
    f%count = 2 * dim
    f%nodes_per_face = merge(4, dim, dim == 3)
    f%vertex_count = 2**dim
    do i = 0, f%vertex_count - 1  ! 2D: counter-clockwise from (x0, y0); 3D: index = x + 2y + 4z
      if (dim == 2) then
        ix = merge(1, 0, i == 1 .or. i == 2)
      else
        ix = iand(i, 1)
      end if
      f%vertex(i * dim + 1) = xs(ix + 1)
      do d = 2, dim
        f%vertex(i * dim + d) = merge(p%upper(d - 1), p%lower(d - 1), btest(i, d - 1))
      end do
    end do
    do k = 0, f%count - 1
      do j = 1, f%nodes_per_face
        if (dim == 1) then
          vtx = k
        else if (dim == 2) then
          vtx = faces2(j, k + 1)
        else
          vtx = faces3(j, k + 1)
        end if
        f%face_vertex(k * f%nodes_per_face + j) = vtx
      end do
      size_ = 1
      do d = 1, dim
        f%normal(k * dim + d) = 0
        if (d - 1 == k / 2) f%normal(k * dim + d) = merge(1.0_c_double, -1.0_c_double, mod(k, 2) == 1)
        s = 0
        lo = huge(1.0_c_double)
        hi = -huge(1.0_c_double)
        do j = 1, f%nodes_per_face
          x = f%vertex(f%face_vertex(k * f%nodes_per_face + j) * dim + d)
          s = s + x
          lo = min(lo, x)
          hi = max(hi, x)
        end do
        f%centre(k * dim + d) = s / f%nodes_per_face
        if (d - 1 /= k / 2) size_ = size_ * (hi - lo)  ! the extent along the face
        f%velocity(k * dim + d) = merge(v, 0.0_c_double, d == 1)
      end do
      f%area(k + 1) = merge(size_, p%area, dim > 1)
    end do
  end subroutine

end module piston_geometry

program rigid_piston
  use, intrinsic :: iso_c_binding
  use cosim_client
  use piston_geometry
  implicit none
  type(c_ptr) :: c
  type(cosim_directive) :: d
  type(piston) :: p
  type(faces) :: f
  real(c_double) :: x, v, force, v_sent, dt, k, theta, v_new
  real(c_double) :: area(max_faces), nx(max_faces), pressure(max_faces), z(max_faces)
  integer(c_int) :: count, phases, n
  integer :: i, nf, unit, ios
  integer(c_long_long) :: set_cycle, set_bytes, csv_bytes
  real(c_double) :: set_time
  real(c_double), allocatable :: state(:)
  character(64) :: sha
  character(:), allocatable :: set
  interface
    integer(c_int) function truncate(path, length) bind(c, name="truncate")  ! POSIX: piston.csv on a restart
      import :: c_int, c_char, c_long
      character(kind=c_char), intent(in) :: path(*)
      integer(c_long), value :: length
    end function
    integer(c_int) function mkdir(path, mode) bind(c, name="mkdir")  ! POSIX: the output directory
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
    end function
  end interface

  if (cosim_create(c, COSIM_ROLE_SOLID) /= COSIM_OK) call stop_with(2, cosim_last_error())
  if (cosim_parse_command_line(c) /= COSIM_OK) call stop_with(2, cosim_last_error())
  if (cosim_set_program(c, "rigid_piston.f90") /= COSIM_OK) call stop_with(2, cosim_last_error())
  call piston_from_scene(c, p)
  call box_faces(p, p%left, p%right, 0.0_c_double, f)
  nf = f%count
  do i = 1, nf
    area(i) = f%area(i)
    nx(i) = f%normal((i - 1) * p%dim + 1)
  end do
  x = 0
  v = 0
  force = 0
  v_sent = 0
  pressure = 0
  z = 0

  set = cosim_restart_set(c)
  if (len(set) > 0) then  ! the state of the set's cycle; piston.csv cut back to where it was then
    if (cosim_client_verify_part(set, part, set_bytes, sha, set_cycle, set_time) /= COSIM_OK) &
      call stop_with(2, "--restart "//set//": "//cosim_last_error())
    if (cosim_read_part(set, part, state) /= COSIM_OK) call stop_with(2, "--restart "//set//": "//cosim_last_error())
    if (size(state) /= state_head + 2 * nf .or. state(1) /= state_version .or. state(9) /= nf .or. &
        state(2) /= real(set_cycle, c_double)) &
      call stop_with(2, "--restart "//set//": "//set//"/"//part//" is not this piston's state of the set's cycle")
    if (cosim_set_restart(c, set_cycle, state(3)) /= COSIM_OK) call stop_with(2, cosim_last_error())
    x = state(4)
    v = state(5)
    force = state(6)
    v_sent = state(7)
    pressure(1:nf) = state(state_head + 1:state_head + nf)
    z(1:nf) = state(state_head + nf + 1:state_head + 2 * nf)
  end if

  ios = mkdir(cosim_out_dir(c)//c_null_char, int(o'777', c_int))  ! fails harmlessly when it exists
  if (len(set) > 0) then
    ios = truncate(cosim_out_dir(c)//"/piston.csv"//c_null_char, int(state(8), c_long))
    if (ios == 0) open (newunit=unit, file=cosim_out_dir(c)//"/piston.csv", status="old", action="write", &
                        position="append", iostat=ios)
  else
    open (newunit=unit, file=cosim_out_dir(c)//"/piston.csv", status="replace", action="write", iostat=ios)
    if (ios == 0) write (unit, '(a)') "time,x,v,force"
  end if
  if (ios /= 0) call stop_with(4, "cannot write "//cosim_out_dir(c)//"/piston.csv")
  if (cosim_hello(c) /= COSIM_OK) call fail("connect")
  do
    if (cosim_next(c, d) /= COSIM_OK) call fail("next")
    if (d%kind == COSIM_STOP) then
      write (0, '(a)') "[rigid_piston.f90] stop: "//cosim_stop_reason(c)
      exit
    end if
    if (d%kind == COSIM_OUTPUT) then
      write (unit, '(g0.12, 3(",", g0.12))') d%time, x, v, force
      flush (unit)
      cycle
    end if
    if (d%kind == COSIM_CHECKPOINT) then  ! the state, written with its checksum and confirmed by the library
      flush (unit)
      inquire (unit=unit, size=csv_bytes)
      state = [state_version, real(cosim_cycle(c), c_double), cosim_time(c), x, v, force, v_sent, &
               real(csv_bytes, c_double), real(nf, c_double), pressure(1:nf), z(1:nf)]
      if (cosim_write_part(c, part, state) /= COSIM_OK) call fail("checkpoint")
      cycle
    end if
    dt = d%dt
    force = 0
    k = 0
    do i = 1, nf
      force = force + (-pressure(i)) * area(i) * nx(i)
      k = k + z(i) * area(i) * (nx(i) * nx(i))
    end do
    if (k > 0 .and. dt > 0) then
      theta = max(0.5_c_double, 1.0_c_double - p%mass / (dt * k))
      v_new = (p%mass * v + dt * ((force + k * v_sent) - ((1.0_c_double - theta) * k) * v)) / &
              (p%mass + (theta * dt) * k)
      force = force + k * (v_sent - ((1.0_c_double - theta) * v + theta * v_new))  ! the Robin part, for the csv
      v = v_new
    else
      v = v + dt * force / p%mass
    end if
    x = x + dt * v
    call box_faces(p, p%left + x, p%right + x, v, f)
    if (cosim_send_faces(c, int(p%dim, c_int), f%count, f%centre, f%normal, f%area, velocity=f%velocity, &
                         nodes_per_face=f%nodes_per_face, vertex_count=f%vertex_count, &
                         vertex_position=f%vertex, face_vertex=f%face_vertex) /= COSIM_OK) call fail("faces")
    if (cosim_propose_dt(c, 1.0_c_double) /= COSIM_OK) call fail("dt")
    if (cosim_receive_states(c, count, phases) /= COSIM_OK) call fail("states")
    if (cosim_states_get(c, COSIM_STATE_FACE_PRESSURE, pressure, int(max_faces, c_int), n) /= COSIM_OK) &
      call fail("states")
    if (cosim_states_get(c, COSIM_STATE_FACE_IMPEDANCE, z, int(max_faces, c_int), n) /= COSIM_OK) call fail("states")
    v_sent = v
  end do
  close (unit)
  call cosim_close(c)

contains

  ! A coupling failure: the coupler is told, exit 5.
  subroutine fail(what)
    character(*), intent(in) :: what
    write (0, '(a)') "[rigid_piston.f90] error: "//what//": "//cosim_last_error()
    call cosim_report_error(c, cosim_last_error())
    call cosim_close(c)
    stop 5, quiet=.true.
  end subroutine

  ! A failure before connecting (2: the command line, 4: the output).
  subroutine stop_with(code, what)
    integer, intent(in) :: code
    character(*), intent(in) :: what
    write (0, '(a)') "[rigid_piston.f90] error: "//what
    call cosim_close(c)
    stop code, quiet=.true.
  end subroutine

end program
