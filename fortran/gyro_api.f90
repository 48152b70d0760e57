! gyro_api: gyro's C API (gyro/gyro.h) for Fortran 2008 programs, through ISO_C_BINDING.
!
!   use gyro_api
!   type(gyro_config) :: cfg          ! a configuration, its fields set by name
!   type(gyro_model) :: model         ! the report's gyro model, in real(c_double) or real(c_float)
!   call cfg%init(GYRO_MODEL_CONFIG)
!   call cfg%set('pitch_inertia', 2.25d0)
!   status = model%create(c_double)   ! or c_float
!   status = model%configure(cfg, why)
!   status = model%uncage(R_earth_to_body, body_rate)
!   status = model%step_slew(dt, R_earth_to_body, slew, spin_hz)   ! arrays of the model's kind
!   call model%gimbal(angles)
!   call model%destroy()
!
! Matrices are Fortran's R(i, j) (this module transposes them to gyro.h's rows). Statuses are
! gyro.h's integers; gyro_status_text() says what one means. docs/embedding.md has an example.
module gyro_api
  use, intrinsic :: iso_c_binding
  implicit none
  private

  public :: c_float, c_double, c_int
  public :: gyro_config, gyro_model, gyro_status_text, gyro_status_name, gyro_nearest_rotation
  public :: gyro_angular_momentum, gyro_rotor_parameters, gyro_rotor_modes, gyro_compute_modes
  public :: gyro_initg_step, gyro_transition, gyro_make_transition, gyro_advance
  public :: gyro_report_sample, gyro_report_sample_get, gyro_frame_rotation, gyro_abi_version

  ! gyro.h's values used here (checked against the library by the module's test).
  integer(c_int), parameter, public :: GYRO_OK = 0, GYRO_OUT_OF_RANGE = 7, GYRO_OUT_OF_MEMORY = 69
  integer(c_int), parameter, public :: GYRO_ABI_WRITTEN_FOR = 1  ! gyro.h's GYRO_ABI_VERSION
  integer(c_int), parameter, public :: GYRO_MODEL_CONFIG = 1, GYRO_PLANT_CONFIG = 2
  integer(c_int), parameter, public :: GYRO_FLAG_GIMBAL_LIMIT = 1, GYRO_FLAG_SMALL_ANGLE = 2

  ! gyro.h's plain structs.
  type, bind(c) :: gyro_rotor_parameters
    real(c_double) :: pitch_inertia = 0, yaw_inertia = 0, friction = 0, angular_momentum = 0
  end type
  type, bind(c) :: gyro_rotor_modes
    real(c_double) :: alpha_1_s = 0, beta_squared_1_s2 = 0, beta_rad_s = 0, natural_rate_rad_s = 0
    real(c_double) :: slow_decay_rate_1_s = 0, fast_decay_rate_1_s = 0, nutation_hz = 0
    integer(c_int) :: regime = 0
  end type
  type, bind(c) :: gyro_transition
    real(c_double) :: coefficients(17) = 0
  end type
  type, bind(c) :: gyro_report_sample
    real(c_double) :: spin_hz = 0, body_rate_rad_s(2) = 0, slew_rate_rad_s(2) = 0, initg_step_s = 0
    integer(c_int) :: steps = 0
  end type
  type, bind(c) :: refusal_c
    integer(c_int) :: status
    type(c_ptr) :: field
    real(c_double) :: value, bound
    integer(c_int) :: relation
    type(c_ptr) :: bound_name, rule
  end type
  type, bind(c) :: step_input_d
    real(c_double) :: dt_s, r(9), body_accel(2), spin_hz, body_rate(3)
  end type
  type, bind(c) :: step_input_f
    real(c_float) :: dt_s, r(9), body_accel(2), spin_hz, body_rate(3)
  end type

  ! A configuration (gyro_model_config or gyro_plant_config) held for the C API, its fields set
  ! by their gyro.h names ("errors.pitch.static_drift_rad_s").
  type :: gyro_config
    integer(c_int) :: kind = 0
    real(c_double), allocatable :: storage(:)
  contains
    procedure :: init => config_init
    procedure :: set_scalar => config_set_scalar
    procedure :: set_vector => config_set_vector
    generic :: set => set_scalar, set_vector
    procedure :: set_choice => config_set_choice
    procedure :: get => config_get
  end type

  ! GyroModel on the heap, in double (kind c_double) or float (c_float).
  type :: gyro_model
    type(c_ptr) :: handle = c_null_ptr
    integer :: real_kind = 0
  contains
    procedure :: create => model_create
    procedure :: destroy => model_destroy
    procedure :: configure => model_configure
    procedure :: uncage_d, uncage_f
    generic :: uncage => uncage_d, uncage_f
    procedure :: step_slew_d, step_slew_f
    generic :: step_slew => step_slew_d, step_slew_f
    procedure :: gimbal_d, gimbal_f
    generic :: gimbal => gimbal_d, gimbal_f
    procedure :: rate_d, rate_f
    generic :: rate => rate_d, rate_f
    procedure :: isaf_angle_d, isaf_angle_f
    generic :: isaf_angle => isaf_angle_d, isaf_angle_f
    procedure :: r_earth_to_gyro_d, r_earth_to_gyro_f
    generic :: r_earth_to_gyro => r_earth_to_gyro_d, r_earth_to_gyro_f
    procedure :: flags => model_flags
  end type

  interface gyro_nearest_rotation
    procedure nearest_rotation_d, nearest_rotation_f
  end interface
  interface gyro_angular_momentum
    procedure angular_momentum_d, angular_momentum_f
  end interface

  ! gyro.h, as called from here.
  interface
    function c_strlen(s) bind(c, name='strlen')
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: c_strlen
    end function
    function gyro_abi_version() bind(c, name='gyro_abi_version')
      import :: c_int
      integer(c_int) :: gyro_abi_version
    end function
    function c_status_text(s) bind(c, name='gyro_status_text')
      import :: c_int, c_ptr
      integer(c_int), value :: s
      type(c_ptr) :: c_status_text
    end function
    function c_status_name(s) bind(c, name='gyro_status_name')
      import :: c_int, c_ptr
      integer(c_int), value :: s
      type(c_ptr) :: c_status_name
    end function
    function c_refusal_text(r, buf, n) bind(c, name='gyro_refusal_text')
      import :: refusal_c, c_char, c_size_t, c_int
      type(refusal_c), intent(in) :: r
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_size_t), value :: n
      integer(c_int) :: c_refusal_text
    end function
    function c_config_size(kind) bind(c, name='gyro_config_size')
      import :: c_int, c_size_t
      integer(c_int), value :: kind
      integer(c_size_t) :: c_config_size
    end function
    function c_config_init(kind, config) bind(c, name='gyro_config_init')
      import :: c_int, c_ptr
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      integer(c_int) :: c_config_init
    end function
    function c_config_set(kind, config, name, values, n) bind(c, name='gyro_config_set')
      import :: c_int, c_ptr, c_char, c_double, c_size_t
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), intent(in) :: values(*)
      integer(c_size_t), value :: n
      integer(c_int) :: c_config_set
    end function
    function c_config_get(kind, config, name, values, n) bind(c, name='gyro_config_get')
      import :: c_int, c_ptr, c_char, c_double, c_size_t
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), intent(out) :: values(*)
      integer(c_size_t), value :: n
      integer(c_int) :: c_config_get
    end function
    function c_config_set_choice(kind, config, name, choice) bind(c, name='gyro_config_set_choice')
      import :: c_int, c_ptr, c_char
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      character(kind=c_char), intent(in) :: name(*), choice(*)
      integer(c_int) :: c_config_set_choice
    end function
    function c_model_create_d() bind(c, name='gyro_model_d_create')
      import :: c_ptr
      type(c_ptr) :: c_model_create_d
    end function
    function c_model_create_f() bind(c, name='gyro_model_f_create')
      import :: c_ptr
      type(c_ptr) :: c_model_create_f
    end function
    subroutine c_model_destroy_d(m) bind(c, name='gyro_model_d_destroy')
      import :: c_ptr
      type(c_ptr), value :: m
    end subroutine
    subroutine c_model_destroy_f(m) bind(c, name='gyro_model_f_destroy')
      import :: c_ptr
      type(c_ptr), value :: m
    end subroutine
    function c_model_configure_d(m, config, refusal) bind(c, name='gyro_model_d_configure')
      import :: c_ptr, c_int, refusal_c
      type(c_ptr), value :: m, config
      type(refusal_c), intent(out) :: refusal
      integer(c_int) :: c_model_configure_d
    end function
    function c_model_configure_f(m, config, refusal) bind(c, name='gyro_model_f_configure')
      import :: c_ptr, c_int, refusal_c
      type(c_ptr), value :: m, config
      type(refusal_c), intent(out) :: refusal
      integer(c_int) :: c_model_configure_f
    end function
    function c_model_uncage_d(m, r, rate, offset) bind(c, name='gyro_model_d_uncage')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: m
      real(c_double), intent(in) :: r(9), rate(2), offset(2)
      integer(c_int) :: c_model_uncage_d
    end function
    function c_model_uncage_f(m, r, rate, offset) bind(c, name='gyro_model_f_uncage')
      import :: c_ptr, c_int, c_float
      type(c_ptr), value :: m
      real(c_float), intent(in) :: r(9), rate(2), offset(2)
      integer(c_int) :: c_model_uncage_f
    end function
    function c_model_step_slew_d(m, in, slew) bind(c, name='gyro_model_d_step_slew')
      import :: c_ptr, c_int, c_double, step_input_d
      type(c_ptr), value :: m
      type(step_input_d), intent(in) :: in
      real(c_double), intent(in) :: slew(2)
      integer(c_int) :: c_model_step_slew_d
    end function
    function c_model_step_slew_f(m, in, slew) bind(c, name='gyro_model_f_step_slew')
      import :: c_ptr, c_int, c_float, step_input_f
      type(c_ptr), value :: m
      type(step_input_f), intent(in) :: in
      real(c_float), intent(in) :: slew(2)
      integer(c_int) :: c_model_step_slew_f
    end function
    function c_model_flags_d(m) bind(c, name='gyro_model_d_flags')
      import :: c_ptr, c_int32_t
      type(c_ptr), value :: m
      integer(c_int32_t) :: c_model_flags_d
    end function
    function c_model_flags_f(m) bind(c, name='gyro_model_f_flags')
      import :: c_ptr, c_int32_t
      type(c_ptr), value :: m
      integer(c_int32_t) :: c_model_flags_f
    end function
    function c_nearest_rotation_d(r, out) bind(c, name='gyro_nearest_rotation_d')
      import :: c_int, c_double
      real(c_double), intent(in) :: r(9)
      real(c_double), intent(out) :: out(9)
      integer(c_int) :: c_nearest_rotation_d
    end function
    function c_nearest_rotation_f(r, out) bind(c, name='gyro_nearest_rotation_f')
      import :: c_int, c_float
      real(c_float), intent(in) :: r(9)
      real(c_float), intent(out) :: out(9)
      integer(c_int) :: c_nearest_rotation_f
    end function
    function angular_momentum_d(spin_hz, spin_inertia) bind(c, name='gyro_angular_momentum_d')
      import :: c_double
      real(c_double), value :: spin_hz, spin_inertia
      real(c_double) :: angular_momentum_d
    end function
    function angular_momentum_f(spin_hz, spin_inertia) bind(c, name='gyro_angular_momentum_f')
      import :: c_float
      real(c_float), value :: spin_hz, spin_inertia
      real(c_float) :: angular_momentum_f
    end function
    function gyro_compute_modes(p, modes) bind(c, name='gyro_compute_modes_d')
      import :: c_int, gyro_rotor_parameters, gyro_rotor_modes
      type(gyro_rotor_parameters), intent(in) :: p
      type(gyro_rotor_modes), intent(out) :: modes
      integer(c_int) :: gyro_compute_modes
    end function
    function gyro_initg_step(p, step_s) bind(c, name='gyro_initg_step_d')
      import :: c_int, c_double, gyro_rotor_parameters
      type(gyro_rotor_parameters), intent(in) :: p
      real(c_double), intent(inout) :: step_s
      integer(c_int) :: gyro_initg_step
    end function
    function gyro_make_transition(p, dt_s, out) bind(c, name='gyro_make_transition_d')
      import :: c_int, c_double, gyro_rotor_parameters, gyro_transition
      type(gyro_rotor_parameters), intent(in) :: p
      real(c_double), value :: dt_s
      type(gyro_transition), intent(inout) :: out
      integer(c_int) :: gyro_make_transition
    end function
    function gyro_advance(tr, torque, state) bind(c, name='gyro_advance_d')
      import :: c_int, c_double, gyro_transition
      type(gyro_transition), intent(in) :: tr
      real(c_double), intent(in) :: torque(2)
      real(c_double), intent(inout) :: state(4)
      integer(c_int) :: gyro_advance
    end function
    function c_report_sample_get(out, config) bind(c, name='gyro_report_sample_get')
      import :: c_int, c_ptr, gyro_report_sample
      type(gyro_report_sample), intent(out) :: out
      type(c_ptr), value :: config
      integer(c_int) :: c_report_sample_get
    end function
    function c_frame_rotation(axis, angle, r) bind(c, name='gyro_frame_rotation_d')
      import :: c_int, c_double
      integer(c_int), value :: axis
      real(c_double), value :: angle
      real(c_double), intent(out) :: r(9)
      integer(c_int) :: c_frame_rotation
    end function
  end interface

contains

  ! A C string (static in the library) as a Fortran string.
  function from_c(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    if (.not. c_associated(p)) then
      s = ''
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: s)
    do i = 1, n
      s(i:i) = chars(i)
    end do
  end function

  function to_c(s) result(c)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: c
    c = trim(s) // c_null_char
  end function

  function gyro_status_text(status) result(s)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: s
    s = from_c(c_status_text(status))
  end function

  function gyro_status_name(status) result(s)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: s
    s = from_c(c_status_name(status))
  end function

  ! ------------------------------------------------------------------------------------------
  subroutine config_init(self, kind)
    class(gyro_config), intent(inout), target :: self
    integer(c_int), intent(in) :: kind
    integer(c_int) :: status
    self%kind = kind
    if (allocated(self%storage)) deallocate(self%storage)
    allocate(self%storage((c_config_size(kind) + 7) / 8 + 1))
    status = c_config_init(kind, c_loc(self%storage))
    if (status /= GYRO_OK) error stop 'gyro_config%init: no such configuration kind'
  end subroutine

  ! Sets a number (or a choice by its index); the status says if the name is unknown.
  function config_set_scalar(self, name, value) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: value
    integer(c_int) :: status
    status = c_config_set(self%kind, c_loc(self%storage), to_c(name), [value], 1_c_size_t)
  end function

  function config_set_vector(self, name, values) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: values(:)
    integer(c_int) :: status
    status = c_config_set(self%kind, c_loc(self%storage), to_c(name), values, size(values, kind=c_size_t))
  end function

  function config_set_choice(self, name, choice) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name, choice
    integer(c_int) :: status
    status = c_config_set_choice(self%kind, c_loc(self%storage), to_c(name), to_c(choice))
  end function

  function config_get(self, name, values) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name
    real(c_double), intent(out) :: values(:)
    integer(c_int) :: status
    status = c_config_get(self%kind, c_loc(self%storage), to_c(name), values, size(values, kind=c_size_t))
  end function

  ! ------------------------------------------------------------------------------------------
  ! A new model computing in real_kind (c_double or c_float); GYRO_OUT_OF_MEMORY if none.
  function model_create(self, real_kind) result(status)
    class(gyro_model), intent(inout) :: self
    integer, intent(in) :: real_kind
    integer(c_int) :: status
    call self%destroy()
    self%real_kind = real_kind
    if (real_kind == c_double) then
      self%handle = c_model_create_d()
    else if (real_kind == c_float) then
      self%handle = c_model_create_f()
    else
      status = GYRO_OUT_OF_RANGE
      return
    end if
    status = merge(GYRO_OK, GYRO_OUT_OF_MEMORY, c_associated(self%handle))
  end function

  subroutine model_destroy(self)
    class(gyro_model), intent(inout) :: self
    if (.not. c_associated(self%handle)) return
    if (self%real_kind == c_double) then
      call c_model_destroy_d(self%handle)
    else
      call c_model_destroy_f(self%handle)
    end if
    self%handle = c_null_ptr
  end subroutine

  ! Configures from a GYRO_MODEL_CONFIG; on a refusal, `why` (if present) says which field, its
  ! value and the bound.
  function model_configure(self, config, why) result(status)
    class(gyro_model), intent(inout) :: self
    class(gyro_config), intent(in), target :: config
    character(len=:), allocatable, intent(out), optional :: why
    integer(c_int) :: status, n
    type(refusal_c) :: r
    character(kind=c_char) :: buf(512)
    integer :: i
    if (self%real_kind == c_double) then
      status = c_model_configure_d(self%handle, c_loc(config%storage), r)
    else
      status = c_model_configure_f(self%handle, c_loc(config%storage), r)
    end if
    if (.not. present(why)) return
    n = c_refusal_text(r, buf, size(buf, kind=c_size_t))
    n = min(n, size(buf) - 1)
    allocate(character(len=n) :: why)
    do i = 1, n
      why(i:i) = buf(i)
    end do
  end function

  ! R_earth_to_body(i, j) and the body's (pitch, yaw) rates; offset (pitch, yaw) optional.
  function uncage_d(self, r, body_rate, offset) result(status)
    class(gyro_model), intent(inout) :: self
    real(c_double), intent(in) :: r(3, 3), body_rate(2)
    real(c_double), intent(in), optional :: offset(2)
    integer(c_int) :: status
    real(c_double) :: off(2)
    off = 0
    if (present(offset)) off = offset
    if (self%real_kind /= c_double) error stop 'gyro_model%uncage: real(c_double) arguments for a c_float model'
    status = c_model_uncage_d(self%handle, reshape(transpose(r), [9]), body_rate, off)
  end function

  function uncage_f(self, r, body_rate, offset) result(status)
    class(gyro_model), intent(inout) :: self
    real(c_float), intent(in) :: r(3, 3), body_rate(2)
    real(c_float), intent(in), optional :: offset(2)
    integer(c_int) :: status
    real(c_float) :: off(2)
    off = 0
    if (present(offset)) off = offset
    if (self%real_kind /= c_float) error stop 'gyro_model%uncage: real(c_float) arguments for a c_double model'
    status = c_model_uncage_f(self%handle, reshape(transpose(r), [9]), body_rate, off)
  end function

  ! One step with the report's command; body_accel (lateral, normal) optional.
  function step_slew_d(self, dt, r, slew, spin_hz, body_accel) result(status)
    class(gyro_model), intent(inout) :: self
    real(c_double), intent(in) :: dt, r(3, 3), slew(2), spin_hz
    real(c_double), intent(in), optional :: body_accel(2)
    integer(c_int) :: status
    type(step_input_d) :: in
    if (self%real_kind /= c_double) error stop 'gyro_model%step_slew: real(c_double) arguments for a c_float model'
    in = step_input_d(dt, reshape(transpose(r), [9]), 0, spin_hz, 0)
    if (present(body_accel)) in%body_accel = body_accel
    status = c_model_step_slew_d(self%handle, in, slew)
  end function

  function step_slew_f(self, dt, r, slew, spin_hz, body_accel) result(status)
    class(gyro_model), intent(inout) :: self
    real(c_float), intent(in) :: dt, r(3, 3), slew(2), spin_hz
    real(c_float), intent(in), optional :: body_accel(2)
    integer(c_int) :: status
    type(step_input_f) :: in
    if (self%real_kind /= c_float) error stop 'gyro_model%step_slew: real(c_float) arguments for a c_double model'
    in = step_input_f(dt, reshape(transpose(r), [9]), 0, spin_hz, 0)
    if (present(body_accel)) in%body_accel = body_accel
    status = c_model_step_slew_f(self%handle, in, slew)
  end function

  ! The readings after the last step: (pitch, yaw) gimbal angles, (theta', psi') rates, the
  ! step's ISAF angles, R_earth_to_gyro(i, j) (the report's ROTEG).
  subroutine gimbal_d(self, v)
    class(gyro_model), intent(in) :: self
    real(c_double), intent(out) :: v(2)
    interface
      subroutine c_pair(m, v) bind(c, name='gyro_model_d_gimbal')
        import :: c_ptr, c_double
        type(c_ptr), value :: m
        real(c_double), intent(out) :: v(2)
      end subroutine
    end interface
    call c_pair(self%handle, v)
  end subroutine
  subroutine gimbal_f(self, v)
    class(gyro_model), intent(in) :: self
    real(c_float), intent(out) :: v(2)
    interface
      subroutine c_pair(m, v) bind(c, name='gyro_model_f_gimbal')
        import :: c_ptr, c_float
        type(c_ptr), value :: m
        real(c_float), intent(out) :: v(2)
      end subroutine
    end interface
    call c_pair(self%handle, v)
  end subroutine
  subroutine rate_d(self, v)
    class(gyro_model), intent(in) :: self
    real(c_double), intent(out) :: v(2)
    interface
      subroutine c_pair(m, v) bind(c, name='gyro_model_d_rate')
        import :: c_ptr, c_double
        type(c_ptr), value :: m
        real(c_double), intent(out) :: v(2)
      end subroutine
    end interface
    call c_pair(self%handle, v)
  end subroutine
  subroutine rate_f(self, v)
    class(gyro_model), intent(in) :: self
    real(c_float), intent(out) :: v(2)
    interface
      subroutine c_pair(m, v) bind(c, name='gyro_model_f_rate')
        import :: c_ptr, c_float
        type(c_ptr), value :: m
        real(c_float), intent(out) :: v(2)
      end subroutine
    end interface
    call c_pair(self%handle, v)
  end subroutine
  subroutine isaf_angle_d(self, v)
    class(gyro_model), intent(in) :: self
    real(c_double), intent(out) :: v(2)
    interface
      subroutine c_pair(m, v) bind(c, name='gyro_model_d_isaf_angle')
        import :: c_ptr, c_double
        type(c_ptr), value :: m
        real(c_double), intent(out) :: v(2)
      end subroutine
    end interface
    call c_pair(self%handle, v)
  end subroutine
  subroutine isaf_angle_f(self, v)
    class(gyro_model), intent(in) :: self
    real(c_float), intent(out) :: v(2)
    interface
      subroutine c_pair(m, v) bind(c, name='gyro_model_f_isaf_angle')
        import :: c_ptr, c_float
        type(c_ptr), value :: m
        real(c_float), intent(out) :: v(2)
      end subroutine
    end interface
    call c_pair(self%handle, v)
  end subroutine

  subroutine r_earth_to_gyro_d(self, r)
    class(gyro_model), intent(in) :: self
    real(c_double), intent(out) :: r(3, 3)
    interface
      subroutine c_r(m, r) bind(c, name='gyro_model_d_R_earth_to_gyro')
        import :: c_ptr, c_double
        type(c_ptr), value :: m
        real(c_double), intent(out) :: r(9)
      end subroutine
    end interface
    real(c_double) :: rows(9)
    call c_r(self%handle, rows)
    r = transpose(reshape(rows, [3, 3]))
  end subroutine

  subroutine r_earth_to_gyro_f(self, r)
    class(gyro_model), intent(in) :: self
    real(c_float), intent(out) :: r(3, 3)
    interface
      subroutine c_r(m, r) bind(c, name='gyro_model_f_R_earth_to_gyro')
        import :: c_ptr, c_float
        type(c_ptr), value :: m
        real(c_float), intent(out) :: r(9)
      end subroutine
    end interface
    real(c_float) :: rows(9)
    call c_r(self%handle, rows)
    r = transpose(reshape(rows, [3, 3]))
  end subroutine

  ! GYRO_FLAG_GIMBAL_LIMIT, GYRO_FLAG_SMALL_ANGLE.
  function model_flags(self) result(flags)
    class(gyro_model), intent(in) :: self
    integer(c_int32_t) :: flags
    if (self%real_kind == c_double) then
      flags = c_model_flags_d(self%handle)
    else
      flags = c_model_flags_f(self%handle)
    end if
  end function

  ! ------------------------------------------------------------------------------------------
  ! The rotation nearest to R(i, j), a direction-cosine matrix that has drifted (gyro.h).
  function nearest_rotation_d(r, out) result(status)
    real(c_double), intent(in) :: r(3, 3)
    real(c_double), intent(out) :: out(3, 3)
    integer(c_int) :: status
    real(c_double) :: rows(9)
    status = c_nearest_rotation_d(reshape(transpose(r), [9]), rows)
    if (status == GYRO_OK) out = transpose(reshape(rows, [3, 3]))
  end function

  function nearest_rotation_f(r, out) result(status)
    real(c_float), intent(in) :: r(3, 3)
    real(c_float), intent(out) :: out(3, 3)
    integer(c_int) :: status
    real(c_float) :: rows(9)
    status = c_nearest_rotation_f(reshape(transpose(r), [9]), rows)
    if (status == GYRO_OK) out = transpose(reshape(rows, [3, 3]))
  end function

  ! A body turning by `angle` about its own y (axis 2) or z (axis 3): R_new = R_axis R_old.
  function gyro_frame_rotation(axis, angle, r) result(status)
    integer, intent(in) :: axis
    real(c_double), intent(in) :: angle
    real(c_double), intent(out) :: r(3, 3)
    integer(c_int) :: status
    real(c_double) :: rows(9)
    status = c_frame_rotation(int(axis - 1, c_int), angle, rows)
    if (status == GYRO_OK) r = transpose(reshape(rows, [3, 3]))
  end function

  ! The report's sample (gyro/report_sample.hpp): its facts, and its gyro into `config`.
  function gyro_report_sample_get(sample, config) result(status)
    type(gyro_report_sample), intent(out) :: sample
    type(gyro_config), intent(inout), target :: config
    integer(c_int) :: status
    call config%init(GYRO_MODEL_CONFIG)
    status = c_report_sample_get(sample, c_loc(config%storage))
  end function

end module gyro_api
