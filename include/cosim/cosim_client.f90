! The cosim coupling client, Fortran interface (docs/clients.md): module cosim_client over the C interface
! (cosim/client.h) with iso_c_binding. Installed as source: compile it with your own compiler next to your
! code (a .mod file only works with the compiler and version that wrote it), link libcosim_client.
!
!   use cosim_client
!   type(c_ptr) :: c
!   type(cosim_directive) :: d
!   ierr = cosim_create(c, COSIM_ROLE_SOLID)
!   ierr = cosim_parse_command_line(c)     ! SCENE --out DIR --coupler EP [--token T] [--set k=v]...
!   ierr = cosim_hello(c)
!   do
!     ierr = cosim_next(c, d)
!     if (d%kind == COSIM_STOP) exit
!     ...                                  ! docs/protocol.md "Writing a solver client"
!   end do
!   call cosim_close(c)
!
! Functions return COSIM_OK (0) or a COSIM_E_* code; cosim_last_error() gives the message. Strings go in as
! Fortran strings (trailing blanks dropped) and come out as allocatable strings.
module cosim_client
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: c_ptr, c_null_ptr, c_double, c_int, c_long_long

  integer(c_int), parameter, public :: COSIM_OK = 0, COSIM_E_ARGUMENT = 1, COSIM_E_SCENE = 2, &
    COSIM_E_REFUSED = 3, COSIM_E_PEER_LOST = 4, COSIM_E_PROTOCOL = 5, COSIM_E_STOPPED = 6, &
    COSIM_E_NOT_FOUND = 7, COSIM_E_FAILED = 8, COSIM_E_CORRUPT = 9
  integer(c_int), parameter, public :: COSIM_ROLE_FLUID = 1, COSIM_ROLE_SOLID = 2
  integer(c_int), parameter, public :: COSIM_ADVANCE = 0, COSIM_OUTPUT = 1, COSIM_CHECKPOINT = 2, COSIM_STOP = 3
  integer(c_int), parameter, public :: COSIM_MODE_IMPEDANCE = 0, COSIM_MODE_STANDARD = 1, &
    COSIM_MODE_CHARACTERISTIC = 2, COSIM_MODE_ROBIN = 3
  integer(c_int), parameter, public :: COSIM_SCHEME_PIPELINED = 0, COSIM_SCHEME_SEQUENTIAL = 1
  integer(c_int), parameter, public :: COSIM_FACE_CENTRE = 0, COSIM_FACE_NORMAL = 1, COSIM_FACE_AREA = 2, &
    COSIM_FACE_VELOCITY = 3, COSIM_FACE_NORMAL_STRESS = 4, COSIM_FACE_IMPEDANCE = 5, &
    COSIM_FACE_VERTEX_POSITION = 6
  integer(c_int), parameter, public :: COSIM_STATE_PRESSURE = 0, COSIM_STATE_NORMAL_VELOCITY = 1, &
    COSIM_STATE_FACE_PRESSURE = 2, COSIM_STATE_FACE_NORMAL_VELOCITY = 3, COSIM_STATE_FACE_WETTED = 4, &
    COSIM_STATE_FACE_IMPEDANCE = 5

  ! One directive of the coupler (the C struct cosim_directive).
  type, bind(c), public :: cosim_directive
    integer(c_int) :: kind = COSIM_STOP
    integer(c_int) :: output_index = 0
    integer(c_long_long) :: cycle = 0
    real(c_double) :: time = 0
    real(c_double) :: dt = 0
  end type

  ! The C functions whose arguments Fortran passes as they are.
  interface
    integer(c_int) function cosim_create(c, role) bind(c, name="cosim_create")
      import :: c_int, c_ptr
      type(c_ptr), intent(out) :: c
      integer(c_int), value :: role
    end function
    integer(c_int) function cosim_set_restart(c, cycle, time) bind(c, name="cosim_set_restart")
      import :: c_int, c_ptr, c_long_long, c_double
      type(c_ptr), value :: c
      integer(c_long_long), value :: cycle
      real(c_double), value :: time
    end function
    integer(c_int) function cosim_set_connect_timeout(c, seconds) bind(c, name="cosim_set_connect_timeout")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: c
      real(c_double), value :: seconds
    end function
    integer(c_int) function cosim_set_ranks(c, ranks) bind(c, name="cosim_set_ranks")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
      integer(c_int), value :: ranks
    end function
    integer(c_int) function cosim_hello(c) bind(c, name="cosim_hello")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
    end function
    integer(c_int) function cosim_next(c, d) bind(c, name="cosim_next")
      import :: c_int, c_ptr, cosim_directive
      type(c_ptr), value :: c
      type(cosim_directive), intent(out) :: d
    end function
    ! velocity, normal_stress, impedance may be left out (0, 0, +inf: rigid); vertex data with nodes_per_face 0.
    integer(c_int) function cosim_send_faces(c, dim, count, centre, normal, area, velocity, normal_stress, &
                                             impedance, nodes_per_face, vertex_count, vertex_position, &
                                             face_vertex) bind(c, name="cosim_send_faces")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: c
      integer(c_int), value :: dim, count, nodes_per_face, vertex_count
      real(c_double), intent(in) :: centre(*), normal(*), area(*)
      real(c_double), intent(in), optional :: velocity(*), normal_stress(*), impedance(*), vertex_position(*)
      integer(c_int), intent(in), optional :: face_vertex(*)  ! 0-based vertex indices
    end function
    integer(c_int) function cosim_receive_faces(c, dim, count, nodes_per_face, vertex_count) &
      bind(c, name="cosim_receive_faces")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
      integer(c_int), intent(out) :: dim, count, nodes_per_face, vertex_count
    end function
    integer(c_int) function cosim_faces_get(c, field, out, capacity, length) bind(c, name="cosim_faces_get")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: c
      integer(c_int), value :: field, capacity
      real(c_double), intent(out) :: out(*)
      integer(c_int), intent(out) :: length
    end function
    integer(c_int) function cosim_faces_vertices(c, out, capacity, length) bind(c, name="cosim_faces_vertices")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
      integer(c_int), value :: capacity
      integer(c_int), intent(out) :: out(*), length
    end function
    integer(c_int) function cosim_send_samples(c, count, phases, alpha, rho, normal_velocity, pressure, &
                                               impedance, wetted) bind(c, name="cosim_send_samples")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: c
      integer(c_int), value :: count, phases
      real(c_double), intent(in) :: alpha(*), rho(*), normal_velocity(*), pressure(*)
      real(c_double), intent(in), optional :: impedance(*)
      integer(c_int), intent(in) :: wetted(*)
    end function
    integer(c_int) function cosim_receive_states(c, count, phases) bind(c, name="cosim_receive_states")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
      integer(c_int), intent(out) :: count, phases
    end function
    integer(c_int) function cosim_states_get(c, field, out, capacity, length) bind(c, name="cosim_states_get")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: c
      integer(c_int), value :: field, capacity
      real(c_double), intent(out) :: out(*)
      integer(c_int), intent(out) :: length
    end function
    integer(c_int) function cosim_propose_dt(c, dt) bind(c, name="cosim_propose_dt")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: c
      real(c_double), value :: dt
    end function
    integer(c_int) function cosim_add_output_seconds(c, seconds) bind(c, name="cosim_add_output_seconds")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: c
      real(c_double), value :: seconds
    end function
    integer(c_int) function cosim_check(c) bind(c, name="cosim_check")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
    end function
    integer(c_int) function cosim_mode(c) bind(c, name="cosim_mode")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
    end function
    integer(c_int) function cosim_scheme(c) bind(c, name="cosim_scheme")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
    end function
    integer(c_long_long) function cosim_cycle(c) bind(c, name="cosim_cycle")
      import :: c_long_long, c_ptr
      type(c_ptr), value :: c
    end function
    real(c_double) function cosim_time(c) bind(c, name="cosim_time")
      import :: c_double, c_ptr
      type(c_ptr), value :: c
    end function
    subroutine cosim_close(c) bind(c, name="cosim_close")
      import :: c_ptr
      type(c_ptr), value :: c
    end subroutine
  end interface
  public :: cosim_create, cosim_set_restart, cosim_set_connect_timeout, cosim_set_ranks, cosim_hello, cosim_next, &
    cosim_send_faces, cosim_receive_faces, cosim_faces_get, cosim_faces_vertices, cosim_send_samples, &
    cosim_receive_states, cosim_states_get, cosim_propose_dt, cosim_add_output_seconds, cosim_check, &
    cosim_mode, cosim_scheme, cosim_cycle, cosim_time, cosim_close

  ! The C functions behind the wrappers below (strings NUL-terminated, C strings returned).
  interface
    type(c_ptr) function last_error_c() bind(c, name="cosim_last_error")
      import :: c_ptr
    end function
    integer(c_int) function set_endpoint_c(c, s) bind(c, name="cosim_set_endpoint")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: s(*)
    end function
    integer(c_int) function set_token_c(c, s) bind(c, name="cosim_set_token")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: s(*)
    end function
    integer(c_int) function set_scene_c(c, s) bind(c, name="cosim_set_scene")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: s(*)
    end function
    integer(c_int) function add_override_c(c, s) bind(c, name="cosim_add_override")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: s(*)
    end function
    integer(c_int) function set_scene_hash_c(c, s) bind(c, name="cosim_set_scene_hash")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: s(*)
    end function
    integer(c_int) function set_program_c(c, s) bind(c, name="cosim_set_program")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: s(*)
    end function
    type(c_ptr) function scene_file_c(c) bind(c, name="cosim_scene_file")
      import :: c_ptr
      type(c_ptr), value :: c
    end function
    type(c_ptr) function out_dir_c(c) bind(c, name="cosim_out_dir")
      import :: c_ptr
      type(c_ptr), value :: c
    end function
    type(c_ptr) function restart_set_c(c) bind(c, name="cosim_restart_set")
      import :: c_ptr
      type(c_ptr), value :: c
    end function
    type(c_ptr) function stop_reason_c(c) bind(c, name="cosim_stop_reason")
      import :: c_ptr
      type(c_ptr), value :: c
    end function
    type(c_ptr) function checkpoint_directory_c(c) bind(c, name="cosim_checkpoint_directory")
      import :: c_ptr
      type(c_ptr), value :: c
    end function
    integer(c_int) function scene_has_c(c, key, value) bind(c, name="cosim_scene_has")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: key(*)
      integer(c_int), intent(out) :: value
    end function
    integer(c_int) function scene_length_c(c, key, value) bind(c, name="cosim_scene_length")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: key(*)
      integer(c_int), intent(out) :: value
    end function
    integer(c_int) function parse_args_c(c, argc, argv) bind(c, name="cosim_parse_args")
      import :: c_int, c_ptr
      type(c_ptr), value :: c
      integer(c_int), value :: argc
      type(c_ptr), intent(in) :: argv(*)
    end function
    integer(c_int) function add_phase_c(c, name, pmin) bind(c, name="cosim_add_phase")
      import :: c_int, c_ptr, c_char, c_double
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), value :: pmin
    end function
    integer(c_int) function scene_number_c(c, key, value) bind(c, name="cosim_scene_number")
      import :: c_int, c_ptr, c_char, c_double
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: key(*)
      real(c_double), intent(out) :: value
    end function
    integer(c_int) function scene_numbers_c(c, key, out, capacity, length) bind(c, name="cosim_scene_numbers")
      import :: c_int, c_ptr, c_char, c_double
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: key(*)
      real(c_double), intent(out) :: out(*)
      integer(c_int), value :: capacity
      integer(c_int), intent(out) :: length
    end function
    integer(c_int) function scene_string_c(c, key, value) bind(c, name="cosim_scene_string")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: key(*)
      type(c_ptr), intent(out) :: value
    end function
    integer(c_int) function confirm_checkpoint_c(c, part, bytes) bind(c, name="cosim_confirm_checkpoint")
      import :: c_int, c_ptr, c_char, c_long_long
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: part(*)
      integer(c_long_long), value :: bytes
    end function
    integer(c_int) function write_part_c(c, part, data, bytes) bind(c, name="cosim_write_part")
      import :: c_int, c_ptr, c_char, c_double, c_long_long
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: part(*)
      real(c_double), intent(in) :: data(*)
      integer(c_long_long), value :: bytes
    end function
    integer(c_int) function verify_part_c(set, part, bytes, sha256, cycle, time) &
      bind(c, name="cosim_client_verify_part")
      import :: c_int, c_char, c_double, c_long_long
      character(kind=c_char), intent(in) :: set(*), part(*)
      integer(c_long_long), intent(out) :: bytes, cycle
      character(kind=c_char), intent(out) :: sha256(65)
      real(c_double), intent(out) :: time
    end function
    integer(c_int) function read_part_c(set, part, out, capacity, length) bind(c, name="cosim_read_part")
      import :: c_int, c_char, c_double, c_long_long
      character(kind=c_char), intent(in) :: set(*), part(*)
      real(c_double), intent(out) :: out(*)
      integer(c_long_long), value :: capacity
      integer(c_long_long), intent(out) :: length
    end function
    subroutine report_error_c(c, reason) bind(c, name="cosim_report_error")
      import :: c_ptr, c_char
      type(c_ptr), value :: c
      character(kind=c_char), intent(in) :: reason(*)
    end subroutine
    integer(c_size_t) function strlen(s) bind(c, name="strlen")
      import :: c_size_t, c_ptr
      type(c_ptr), value :: s
    end function
  end interface

  public :: cosim_last_error, cosim_parse_command_line, cosim_add_phase, cosim_scene_has, cosim_scene_length, &
    cosim_scene_number, cosim_scene_numbers, cosim_scene_string, cosim_confirm_checkpoint, cosim_report_error, &
    cosim_set_endpoint, cosim_set_token, cosim_set_scene, cosim_add_override, cosim_set_scene_hash, &
    cosim_set_program, cosim_scene_file, cosim_out_dir, cosim_restart_set, cosim_stop_reason, &
    cosim_checkpoint_directory, cosim_write_part, cosim_client_verify_part, cosim_read_part

contains

  ! A Fortran string as a NUL-terminated C string (trailing blanks dropped).
  pure function cstr(s) result(r)
    character(*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: r
    r = trim(s)//c_null_char
  end function

  ! A C string as a Fortran string ("" for a null pointer).
  function fstr(p) result(r)
    type(c_ptr), intent(in) :: p
    character(:), allocatable :: r
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    if (.not. c_associated(p)) then
      r = ""
      return
    end if
    n = int(strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate (character(n) :: r)
    do i = 1, n
      r(i:i) = chars(i)
    end do
  end function

  ! The message of the last failed call.
  function cosim_last_error() result(r)
    character(:), allocatable :: r
    r = fstr(last_error_c())
  end function

  ! Reads the program's command line: SCENE --out DIR --coupler EP [--token T] [--set k=v]... [--restart SET].
  integer(c_int) function cosim_parse_command_line(c) result(ierr)
    type(c_ptr), intent(in) :: c
    type :: arg_text
      character(kind=c_char, len=:), allocatable :: s
    end type
    type(arg_text), allocatable, target :: args(:)
    type(c_ptr), allocatable :: argv(:)
    integer :: i, n, length
    n = command_argument_count()
    allocate (args(0:n), argv(0:n))
    do i = 0, n
      call get_command_argument(i, length=length)
      allocate (character(kind=c_char, len=length + 1) :: args(i)%s)
      call get_command_argument(i, args(i)%s(1:length))
      args(i)%s(length + 1:length + 1) = c_null_char
      argv(i) = c_loc(args(i)%s)
    end do
    ierr = parse_args_c(c, int(n + 1, c_int), argv)
  end function

  integer(c_int) function cosim_set_endpoint(c, s) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: s
    ierr = set_endpoint_c(c, cstr(s))
  end function

  integer(c_int) function cosim_set_token(c, s) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: s
    ierr = set_token_c(c, cstr(s))
  end function

  integer(c_int) function cosim_set_scene(c, s) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: s
    ierr = set_scene_c(c, cstr(s))
  end function

  integer(c_int) function cosim_add_override(c, s) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: s
    ierr = add_override_c(c, cstr(s))
  end function

  integer(c_int) function cosim_set_scene_hash(c, s) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: s
    ierr = set_scene_hash_c(c, cstr(s))
  end function

  integer(c_int) function cosim_set_program(c, s) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: s
    ierr = set_program_c(c, cstr(s))
  end function

  function cosim_scene_file(c) result(r)
    type(c_ptr), intent(in) :: c
    character(:), allocatable :: r
    r = fstr(scene_file_c(c))
  end function

  function cosim_out_dir(c) result(r)
    type(c_ptr), intent(in) :: c
    character(:), allocatable :: r
    r = fstr(out_dir_c(c))
  end function

  function cosim_restart_set(c) result(r)
    type(c_ptr), intent(in) :: c
    character(:), allocatable :: r
    r = fstr(restart_set_c(c))
  end function

  function cosim_stop_reason(c) result(r)
    type(c_ptr), intent(in) :: c
    character(:), allocatable :: r
    r = fstr(stop_reason_c(c))
  end function

  function cosim_checkpoint_directory(c) result(r)
    type(c_ptr), intent(in) :: c
    character(:), allocatable :: r
    r = fstr(checkpoint_directory_c(c))
  end function

  ! Fluid: its phases in sample order, with the lowest pressure each admits [Pa].
  integer(c_int) function cosim_add_phase(c, name, min_pressure) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: name
    real(c_double), intent(in) :: min_pressure
    ierr = add_phase_c(c, cstr(name), min_pressure)
  end function

  ! The scene with its overrides; keys like "solid.blocks.1.density" (list entries from 0).
  integer(c_int) function cosim_scene_has(c, key, present) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: key
    logical, intent(out) :: present
    integer(c_int) :: p
    ierr = scene_has_c(c, cstr(key), p)
    present = p /= 0
  end function

  integer(c_int) function cosim_scene_length(c, key, length) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: key
    integer, intent(out) :: length
    integer(c_int) :: n
    ierr = scene_length_c(c, cstr(key), n)
    length = n
  end function

  integer(c_int) function cosim_scene_number(c, key, value) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: key
    real(c_double), intent(out) :: value
    ierr = scene_number_c(c, cstr(key), value)
  end function

  ! A list of numbers into an allocatable array.
  integer(c_int) function cosim_scene_numbers(c, key, values) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: key
    real(c_double), allocatable, intent(out) :: values(:)
    integer(c_int) :: capacity, n
    ierr = scene_length_c(c, cstr(key), capacity)
    if (ierr /= COSIM_OK) return
    allocate (values(max(capacity, 1_c_int)))
    ierr = scene_numbers_c(c, cstr(key), values, capacity, n)
    if (ierr == COSIM_OK) values = values(1:n)
  end function

  integer(c_int) function cosim_scene_string(c, key, value) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: key
    character(:), allocatable, intent(out) :: value
    type(c_ptr) :: p
    p = c_null_ptr
    ierr = scene_string_c(c, cstr(key), p)
    value = fstr(p)
  end function

  ! Answers COSIM_CHECKPOINT: this solver's part (a file name in cosim_checkpoint_directory) is written.
  integer(c_int) function cosim_confirm_checkpoint(c, part, bytes) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: part
    integer(c_long_long), intent(in) :: bytes
    ierr = confirm_checkpoint_c(c, cstr(part), bytes)
  end function

  ! Answers COSIM_CHECKPOINT in one call: `values` written as the file `part` of the set (whole or absent), its
  ! SHA-256 beside it in PART.sha256, and the part confirmed to the coupler (cosim_write_part).
  integer(c_int) function cosim_write_part(c, part, values) result(ierr)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: part
    real(c_double), intent(in) :: values(:)
    ierr = write_part_c(c, cstr(part), values, int(size(values), c_long_long) * 8_c_long_long)
  end function

  ! Checks `part` of the checkpoint set directory `set` against its manifest (size, SHA-256, the set's cycle);
  ! gives its size [bytes], SHA-256 (64 hex digits), the set's cycle and time. COSIM_E_CORRUPT names the file.
  integer(c_int) function cosim_client_verify_part(set, part, bytes, sha256, cycle, time) result(ierr)
    character(*), intent(in) :: set, part
    integer(c_long_long), intent(out) :: bytes, cycle
    character(len=64), intent(out) :: sha256
    real(c_double), intent(out) :: time
    character(kind=c_char) :: sha(65)
    integer :: i
    sha = c_null_char
    ierr = verify_part_c(cstr(set), cstr(part), bytes, sha, cycle, time)
    do i = 1, 64
      sha256(i:i) = sha(i)
    end do
  end function

  ! A part of doubles (written by cosim_write_part) into an allocatable array, after the manifest's checks made on
  ! the bytes read.
  integer(c_int) function cosim_read_part(set, part, values) result(ierr)
    character(*), intent(in) :: set, part
    real(c_double), allocatable, intent(out) :: values(:)
    integer(c_long_long) :: bytes, cycle, length
    character(len=64) :: sha
    real(c_double) :: time
    ierr = cosim_client_verify_part(set, part, bytes, sha, cycle, time)
    if (ierr /= COSIM_OK) return
    allocate (values(max(bytes / 8_c_long_long, 1_c_long_long)))
    if (mod(bytes, 8_c_long_long) /= 0) then
      ierr = COSIM_E_ARGUMENT
      return
    end if
    ierr = read_part_c(cstr(set), cstr(part), values, bytes, length)
    if (ierr == COSIM_OK) values = values(1:length / 8)
  end function

  ! Tells the coupler this solver cannot go on (call it before stopping with a non-zero code).
  subroutine cosim_report_error(c, reason)
    type(c_ptr), intent(in) :: c
    character(*), intent(in) :: reason
    call report_error_c(c, cstr(reason))
  end subroutine

end module cosim_client
